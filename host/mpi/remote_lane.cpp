#include "mpi/remote_lane.h"

#include "core/error.h"
#include "core/interrupt.h"
#include "mpi/mpi_transport.h"

namespace kasha {

RemoteLane::RemoteLane(int rank, int device, const std::string& integrator,
                       const mpi::RemoteDevice& info)
    : rank_(rank), device_(device), info_(info) {
  rename(integrator);
}

std::string RemoteLane::description() const {
  return "rank " + std::to_string(rank_) + " device " + std::to_string(device_) + " (" +
         info_.name + ")";
}

// No interrupt is checked here: rank 0's RankWatch (mpi/rank_control.h) tells the rank, which
// then ends its work early and answers, or gives up on a rank that does not answer.
void RemoteLane::send(const mpi::Request& request) {
  mpi::Outgoing(rank_, device_, mpi::encode(request)).wait();
}

mpi::Reply RemoteLane::receive(mpi::Kind expected) {
  mpi::Backoff backoff;
  for (;;) {
    if (std::optional<std::vector<char>> bytes = mpi::try_receive(rank_, device_)) {
      mpi::Reply reply = mpi::decode_reply(*bytes);
      if (reply.kind == mpi::Kind::error)
        throw Error("rank " + std::to_string(rank_) + ": " + reply.error);
      if (reply.kind != expected)
        throw Error("rank " + std::to_string(rank_) + ": answered with a message of another kind");
      return reply;
    }
    backoff.pause();
  }
}

PassResult RemoteLane::render_pass(int pass) {
  mpi::Request r;
  r.kind = mpi::Kind::pass;
  r.pass = pass;
  r.seconds_left = mpi::seconds_left(control_);
  r.interrupted = interrupt_requested();
  send(r);
  return std::move(receive(mpi::Kind::result).result);
}

void RemoteLane::take_inputs(const PassInputs& inputs) {
  mpi::Request r;
  r.kind = mpi::Kind::inputs;
  r.seconds_left = mpi::seconds_left(control_);
  r.interrupted = interrupt_requested();
  r.inputs = inputs;
  send(r);  // answered only by a failure, which the next chunk's answer carries
}

ChunkResult RemoteLane::trace_chunk(int pass, size_t first, size_t count,
                                    std::atomic<size_t>& progress) {
  mpi::Request r;
  r.kind = mpi::Kind::chunk;
  r.pass = pass;
  r.first = first;
  r.count = count;
  r.interrupted = interrupt_requested();
  send(r);
  ChunkResult c = std::move(receive(mpi::Kind::chunk_result).chunk);
  progress += static_cast<size_t>(c.traced);
  return c;
}

}  // namespace kasha
