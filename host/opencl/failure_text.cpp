#include "opencl/failure_text.h"

#include "core/error.h"
#include "core/interrupt.h"
#include "core/printable.h"
#include "opencl/device.h"

namespace kasha {

std::string failure_text() {
  try {
    throw;
  } catch (const Interrupted&) {
    return "interrupted";
  } catch (const cl::Error& e) {
    return as_one_line("OpenCL: " + cl_error_text(e));
  } catch (const Error& e) {
    return as_one_line(e.what());
  } catch (const std::exception& e) {
    // A backstop: library errors are translated where they are raised, with their WHERE; one
    // that got past still reads as a line of kasha's, not "[json.exception…]" or "filesystem
    // error".
    return library_error_text(e);
  } catch (...) {
    return "an unknown failure";
  }
}

}  // namespace kasha
