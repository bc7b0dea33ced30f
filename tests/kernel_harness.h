#pragma once
// Unit tests of kernel routines: a test kernel from a source string whose quoted #includes name
// the embedded kernel headers, built for device 0, run over a 1-D range, its float outputs read
// back.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "opencl/device.h"
#include "opencl/kernel_program.h"
#include "opencl/upload.h"

namespace kasha::test {

// Device 0, shared by the kernel tests.
ClContext& test_device();

// Definitions for the headers that need them: 4 bins, RGB film, gloss, no fluorescence.
KernelDefines test_kernel_defines();

class TestKernel {
 public:
  // Builds `entry` from `source`; `name` labels the source in #line markers and build errors.
  TestKernel(const std::string& source, const std::string& name, const std::string& entry,
             const KernelDefines& defines = test_kernel_defines());

  // Argument `index`: a read-only buffer holding `data` (floats, ints, kernel structs).
  template <typename T>
  void input(int index, const std::vector<T>& data) {
    set_buffer(index, upload(cl_, data));
  }
  // Argument `index`: a buffer made elsewhere (upload_tables' packed tables).
  void buffer(int index, cl::Buffer buffer) { set_buffer(index, std::move(buffer)); }
  // Argument `index`: a scalar (int, float, ...).
  template <typename T>
  void scalar(int index, T value) {
    kernel_.setArg(index, value);
  }
  // The kernel itself, for DeviceScene::bind.
  cl::Kernel& handle() { return kernel_; }
  // Argument `index`: a buffer of `count` floats the kernel writes, read back by read().
  void output(int index, size_t count);

  // Runs `items` work items (global ids 0 .. items-1) and waits for them.
  void run(size_t items);
  // The contents of output buffer `index` after run().
  std::vector<float> read(int index);
  // The usual sampling run: `uniforms` as argument `in`, `per_item` floats out per work item as
  // argument `out`, `items` work items; returns what they wrote.
  std::vector<float> sample(int in, const std::vector<float>& uniforms, int out, size_t per_item,
                            size_t items);

 private:
  void set_buffer(int index, cl::Buffer buffer);

  ClContext& cl_;
  cl::Kernel kernel_;
  std::map<int, cl::Buffer> buffers_;  // kept alive while the kernel may use them
  std::map<int, size_t> output_count_;
};

}  // namespace kasha::test
