#include "opencl/failure_text.h"

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
  } catch (const std::exception& e) {
    return as_one_line(e.what());
  } catch (...) {
    return "an unknown failure";
  }
}

}  // namespace kasha
