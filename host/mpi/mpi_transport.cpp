#include "mpi/mpi_transport.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <string>
#include <thread>

#include "core/error.h"

#ifdef KASHA_HAVE_MPI
#include <mpi.h>
#endif

namespace kasha::mpi {

void Outgoing::yield() {
  std::this_thread::yield();
}

void Backoff::pause() {
  std::this_thread::sleep_for(std::chrono::microseconds(micros_));
  micros_ = std::min(2 * micros_, 1000);
}

#ifdef KASHA_HAVE_MPI

namespace {
void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw Error(std::string("MPI: ") + what + ": " + std::string(text, length));
}
}  // namespace

std::optional<std::vector<char>> try_receive(int source, int tag) {
  int found = 0;
  MPI_Message message;
  MPI_Status status;
  // A matched probe: the message found is the one received, whichever threads probe alongside.
  check(MPI_Improbe(source, tag, MPI_COMM_WORLD, &found, &message, &status), "probe");
  if (!found) return std::nullopt;
  int count = 0;
  check(MPI_Get_count(&status, MPI_BYTE, &count), "message size");
  std::vector<char> bytes(static_cast<size_t>(count));
  check(MPI_Mrecv(bytes.data(), count, MPI_BYTE, &message, MPI_STATUS_IGNORE), "receive");
  return bytes;
}

struct Outgoing::State {
  std::vector<char> bytes;
  MPI_Request request = MPI_REQUEST_NULL;
  bool done = false;
};

Outgoing::Outgoing(int destination, int tag, std::vector<char> bytes)
    : state_(std::make_unique<State>()) {
  state_->bytes = std::move(bytes);
  // MPI counts in int: messages beyond 2 GiB would need splitting, far beyond any image's.
  if (state_->bytes.size() > static_cast<size_t>(INT_MAX))
    throw Error("MPI: a message of " + std::to_string(state_->bytes.size()) +
                " bytes is beyond MPI's 2 GiB count");
  check(MPI_Isend(state_->bytes.data(), static_cast<int>(state_->bytes.size()), MPI_BYTE,
                  destination, tag, MPI_COMM_WORLD, &state_->request),
        "send");
}

Outgoing::~Outgoing() {
  if (state_->done) return;
  MPI_Request_free(&state_->request);
  state_.release();  // MPI may still read the bytes
}

bool Outgoing::done() {
  if (state_->done) return true;
  int flag = 0;
  check(MPI_Test(&state_->request, &flag, MPI_STATUS_IGNORE), "send");
  state_->done = flag != 0;
  return state_->done;
}

#else

struct Outgoing::State {};

static Error no_mpi() {
  return Error("MPI: this kasha was built without MPI (KASHA_MPI=OFF)");
}

std::optional<std::vector<char>> try_receive(int, int) {
  throw no_mpi();
}
Outgoing::Outgoing(int, int, std::vector<char>) {
  throw no_mpi();
}
Outgoing::~Outgoing() = default;
bool Outgoing::done() {
  return true;
}

#endif

}  // namespace kasha::mpi
