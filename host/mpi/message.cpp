#include "mpi/message.h"

#include "core/error.h"

namespace kasha {

void MessageWriter::append(const void* data, size_t size) {
  if (size == 0) return;
  const size_t at = bytes_.size();
  bytes_.resize(at + size);
  std::memcpy(bytes_.data() + at, data, size);
}

MessageWriter& MessageWriter::put(const std::string& text) {
  put<uint64_t>(text.size());
  append(text.data(), text.size());
  return *this;
}

void MessageReader::copy(void* out, size_t size) {
  if (size > bytes_.size() - at_) truncated();
  if (size > 0) std::memcpy(out, bytes_.data() + at_, size);
  at_ += size;
}

void MessageReader::truncated() const {
  throw Error("MPI: a message of " + std::to_string(bytes_.size()) +
              " bytes is shorter than its contents (ranks running different kasha builds?)");
}

std::string MessageReader::get_string() {
  const uint64_t n = get<uint64_t>();
  if (n > bytes_.size() - at_) truncated();
  std::string text(bytes_.data() + at_, n);
  at_ += n;
  return text;
}

void MessageReader::end() const {
  if (at_ != bytes_.size())
    throw Error("MPI: a message of " + std::to_string(bytes_.size()) + " bytes has " +
                std::to_string(bytes_.size() - at_) +
                " bytes left over (ranks running different kasha builds?)");
}

}  // namespace kasha
