#pragma once
// The Khronos C++ bindings, configured once (version macros and exceptions come from CMake).
#include <CL/opencl.hpp>
