#pragma once
// The bytes of one MPI message: values appended in order by a writer and read back in the same
// order by a reader, in the machine's own layout (every rank of a job runs the same binary on the
// same kind of machine). Doubles travel as their bytes, so what a rank computed arrives bit for
// bit. A reader throws kasha::Error on a message shorter than what is read from it.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace kasha {

class MessageWriter {
 public:
  template <typename T>
  MessageWriter& put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(&value, sizeof value);
    return *this;
  }
  template <typename T>
  MessageWriter& put(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(values.size());
    append(values.data(), values.size() * sizeof(T));
    return *this;
  }
  MessageWriter& put(const std::string& text);

  const std::vector<char>& bytes() const { return bytes_; }
  std::vector<char> take() { return std::move(bytes_); }

 private:
  void append(const void* data, size_t size);
  std::vector<char> bytes_;
};

class MessageReader {
 public:
  explicit MessageReader(const std::vector<char>& bytes) : bytes_(bytes) {}

  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    copy(&value, sizeof value);
    return value;
  }
  template <typename T>
  std::vector<T> get_vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = get<uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(T)) truncated();
    std::vector<T> values(n);
    copy(values.data(), n * sizeof(T));
    return values;
  }
  std::string get_string();

  // Throws unless every byte was read: a reader and a writer that disagree fail loudly.
  void end() const;

 private:
  void copy(void* out, size_t size);
  [[noreturn]] void truncated() const;
  const std::vector<char>& bytes_;
  size_t at_ = 0;
};

}  // namespace kasha
