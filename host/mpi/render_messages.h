#pragma once
// What rank 0 and a rank's device say to each other (mpi/remote_lane.h, mpi/render_server.h), one
// message each way per request: rank 0 asks for a pass (backward, forward, debug) or, for photon
// mapping, hands over a pass's inputs and asks for chunks of its photons; the device answers with
// the pass's or the chunk's result — every sum as its bytes, so the image is the one a device of
// rank 0 would make — or with the one line of what failed. A pass's `kept` image does not travel:
// only photon mapping's main device keeps one, and that is always rank 0's.
#include <cstdint>
#include <string>
#include <vector>

#include "film/pass_result.h"
#include "render/pass_chunks.h"
#include "render/pass_control.h"

namespace kasha::mpi {

enum class Kind : char {
  pass = 'P',    // rank 0: render pass `pass`
  inputs = 'I',  // rank 0: the pass's visible points and radii (no answer unless it fails)
  chunk = 'C',   // rank 0: trace and gather photons [first, first + count) of pass `pass`
  result = 'R',  // the device: a pass's result
  chunk_result = 'K',
  error = 'E',  // the device: what failed, one line
  hello = 'H',  // a rank: its devices
};

struct Request {
  Kind kind = Kind::pass;
  int pass = 0;
  uint64_t first = 0, count = 0;
  double seconds_left = -1;  // to the pass's deadline (--time), or < 0: none
  bool interrupted = false;  // rank 0 was interrupted: end the work as soon as it can
  PassInputs inputs;
};

struct Reply {
  Kind kind = Kind::error;
  PassResult result;
  ChunkResult chunk;
  std::string error;
};

struct RemoteDevice {
  std::string name;
  uint64_t capacity = 0;  // photon mapping's store, in records (0 for other integrators)
};

struct Hello {
  std::string error;   // why the rank has no devices; empty when it has
  std::string render;  // what the rank renders (render_fingerprint): rank 0's, or refused
  std::vector<RemoteDevice> devices;
};

std::vector<char> encode(const Request& request);
Request decode_request(const std::vector<char>& bytes);
std::vector<char> encode(const Reply& reply);
Reply decode_reply(const std::vector<char>& bytes);
std::vector<char> encode(const Hello& hello);
Hello decode_hello(const std::vector<char>& bytes);

// A deadline as seconds from now, and back: clocks of different machines do not agree.
double seconds_left(const PassControl& control);
PassControl control_for(double seconds_left);

}  // namespace kasha::mpi
