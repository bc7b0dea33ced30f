#include "kernel_harness.h"

#include <algorithm>
#include <utility>

#include "core/error.h"

namespace kasha::test {

ClContext& test_device() {
  static ClContext context(0);
  return context;
}

KernelDefines test_kernel_defines() {
  return {{"KASHA_BINS", "4"},
          {"KASHA_FILM_ROWS", "3"},
          {"KASHA_SPECTRAL_FILM", "0"},
          {"KASHA_FLUORESCENCE", "0"},
          {"KASHA_GLOSS", "1"}};
}

TestKernel::TestKernel(const std::string& source, const std::string& name, const std::string& entry,
                       const KernelDefines& defines)
    : cl_(test_device()) {
  cl::Program program =
      build_program(cl_, assemble_kernel_source_text(source, name), defines, name);
  try {
    kernel_ = cl::Kernel(program, entry.c_str());
  } catch (const cl::Error& e) {
    throw Error("OpenCL: no kernel " + entry + " in " + name + ": " + cl_error_text(e));
  }
}

void TestKernel::set_buffer(int index, cl::Buffer buffer) {
  kernel_.setArg(index, buffer);
  buffers_[index] = std::move(buffer);
  output_count_.erase(index);
}

void TestKernel::output(int index, size_t count) {
  set_buffer(index, cl::Buffer(cl_.context(), CL_MEM_WRITE_ONLY,
                               std::max<size_t>(count, 1) * sizeof(float)));
  output_count_[index] = count;
}

void TestKernel::run(size_t items) {
  cl_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(items), cl::NullRange);
  cl_.queue().finish();
}

std::vector<float> TestKernel::sample(int in, const std::vector<float>& uniforms, int out,
                                      size_t per_item, size_t items) {
  input(in, uniforms);
  output(out, per_item * items);
  run(items);
  return read(out);
}

std::vector<float> TestKernel::read(int index) {
  auto it = output_count_.find(index);
  if (it == output_count_.end())
    throw Error("TestKernel: argument " + std::to_string(index) + " is not an output");
  std::vector<float> out(it->second);
  if (!out.empty())
    cl_.queue().enqueueReadBuffer(buffers_.at(index), CL_TRUE, 0, out.size() * sizeof(float),
                                  out.data());
  return out;
}

}  // namespace kasha::test
