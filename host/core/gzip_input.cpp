#include "core/gzip_input.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable.h"

namespace kasha {

bool is_gzip_name(const std::string& path) {
  const size_t n = path.size();
  return n > 3 && path[n - 3] == '.' &&
         std::tolower(static_cast<unsigned char>(path[n - 2])) == 'g' &&
         std::tolower(static_cast<unsigned char>(path[n - 1])) == 'z';
}

namespace {

// A z_stream that ends itself.
struct Inflater {
  z_stream z{};
  bool open = false;
  ~Inflater() {
    if (open) inflateEnd(&z);
  }
};

}  // namespace

std::string gunzip(const std::string& compressed, const std::string& path,
                   std::uint64_t max_bytes) {
  const std::string where = printable(path) + ": ";
  Inflater in;
  // 16 + 15: a gzip header and trailer around the largest deflate window.
  if (inflateInit2(&in.z, 16 + 15) != Z_OK) throw Error(where + "cannot start decompressing");
  in.open = true;
  in.z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  in.z.avail_in = static_cast<uInt>(std::min<size_t>(compressed.size(), 1u << 30));
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    in.z.next_out = reinterpret_cast<Bytef*>(buffer);
    in.z.avail_out = sizeof buffer;
    const int r = inflate(&in.z, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - in.z.avail_out);
    if (out.size() > max_bytes)
      throw Error(where + "decompresses to more than " +
                  (max_bytes >= (1u << 20) ? std::to_string(max_bytes >> 20) + " MiB"
                                           : std::to_string(max_bytes) + " bytes") +
                  ", the most an input of this kind may have");
    if (r == Z_STREAM_END) {
      // gzip files may hold several members one after another (gzip's own reader reads them all).
      if (in.z.avail_in == 0) return out;
      if (inflateReset(&in.z) != Z_OK) throw Error(where + "cannot go on decompressing");
      continue;
    }
    if (r == Z_OK) continue;
    if (r == Z_BUF_ERROR && in.z.avail_in == 0)
      throw Error(where + "the compressed data ends early (a truncated .gz file)");
    if (r == Z_MEM_ERROR) throw Error(where + "out of memory while decompressing");
    throw Error(where + "is not valid gzip data (corrupt or not compressed)");
  }
}

std::string read_input_file_inflated(const std::string& path, std::uint64_t max_bytes) {
  std::string bytes = read_input_file(path, max_bytes);
  if (!is_gzip_name(path)) return bytes;
  return gunzip(bytes, path, max_bytes);
}

}  // namespace kasha
