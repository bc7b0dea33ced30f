// The fitted RGB → spectrum table (host/tools/rgb_spectrum_table.cpp writes it at build time),
// linked in as it is: the assembler's .incbin copies the file's bytes into read-only data, so
// 9 MiB of coefficients cost no compile time.
#include <cstddef>

#ifndef KASHA_RGB_TABLE_FILE
#error "the build defines KASHA_RGB_TABLE_FILE"
#endif

__asm__(
    ".section .rodata\n"
    ".balign 16\n"
    "kasha_rgb_table_begin:\n"
    ".incbin \"" KASHA_RGB_TABLE_FILE
    "\"\n"
    "kasha_rgb_table_end:\n"
    ".previous\n");

extern "C" const float kasha_rgb_table_begin[];
extern "C" const char kasha_rgb_table_end[];

namespace kasha {

const float* rgb_table_data(std::size_t* floats) {
  *floats = static_cast<std::size_t>(kasha_rgb_table_end -
                                     reinterpret_cast<const char*>(kasha_rgb_table_begin)) /
            sizeof(float);
  return kasha_rgb_table_begin;
}

}  // namespace kasha
