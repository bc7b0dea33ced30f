#include "mpi/render_server.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "core/error.h"
#include "core/interrupt.h"
#include "mpi/mpi_transport.h"
#include "mpi/mpi_world.h"
#include "mpi/render_messages.h"
#include "opencl/failure_text.h"
#include "render/render_job.h"

namespace kasha {

namespace {

// Sends and waits until the bytes are out, or rank 0 has ended the job.
void send(int tag, std::vector<char> bytes) {
  mpi::Outgoing(0, tag, std::move(bytes)).wait([] { return MpiWorld::get().stopped(); });
}

// A test hook: KASHA_TEST_KILL_RANK=R makes rank R die by SIGKILL as its second request arrives,
// mid-render, as a rank whose machine fails would.
bool dies_here(int requests) {
  const char* rank = std::getenv("KASHA_TEST_KILL_RANK");
  return rank && std::atoi(rank) == MpiWorld::get().rank() && requests == 2;
}

// Answers rank 0's requests for device `tag` of this rank until rank 0 says stop.
void serve_device(int tag, Integrator& integrator) {
  ChunkWorker* worker = integrator.chunk_worker();
  std::string inputs_failed;  // a pass's inputs that failed to arrive: the next chunk's answer
  std::atomic<size_t> progress{0};
  int requests = 0;
  mpi::Backoff backoff;
  while (!MpiWorld::get().stopped()) {
    std::optional<std::vector<char>> bytes = mpi::try_receive(0, tag);
    if (!bytes) {
      backoff.pause();
      continue;
    }
    backoff.reset();
    mpi::Reply reply;
    try {
      const mpi::Request request = mpi::decode_request(*bytes);
      if (request.interrupted) request_interrupt();
      if (request.kind != mpi::Kind::inputs && dies_here(++requests)) std::raise(SIGKILL);
      if (request.kind == mpi::Kind::pass) {
        integrator.set_control(mpi::control_for(request.seconds_left));
        reply.result = integrator.render_pass(request.pass);
        reply.kind = mpi::Kind::result;
      } else if (!worker) {
        throw Error("photon mapping's chunks asked of the " + integrator.name() + " integrator");
      } else if (request.kind == mpi::Kind::inputs) {
        try {
          worker->set_chunk_control(mpi::control_for(request.seconds_left));
          worker->take_inputs(request.inputs);
          inputs_failed.clear();
        } catch (...) {
          inputs_failed = failure_text();
        }
        continue;  // no answer
      } else {
        if (!inputs_failed.empty()) throw Error(inputs_failed);
        reply.chunk = worker->trace_chunk(request.pass, request.first, request.count, progress);
        reply.kind = mpi::Kind::chunk_result;
      }
    } catch (...) {
      reply = mpi::Reply{};
      reply.kind = mpi::Kind::error;
      reply.error = failure_text();
    }
    send(tag, mpi::encode(reply));
  }
}

}  // namespace

void refuse_render(const std::string& why) {
  mpi::Hello hello;
  hello.error = why;
  send(mpi::kHelloTag, mpi::encode(hello));
}

int serve_render(const RenderSpec& spec) {
  install_interrupt_handler();  // SIGTERM from mpirun ends the work in flight early
  mpi::Hello hello;
  hello.render = render_fingerprint(spec);
  std::unique_ptr<Scene> scene;
  std::unique_ptr<DeviceSet> devices;
  std::vector<std::unique_ptr<RenderJob>> jobs;
  try {
    scene = std::make_unique<Scene>(load_scene(spec.scene, spec.grid(), spec.lamp, spec.materials));
    devices = std::make_unique<DeviceSet>(spec.device);
    if (devices->size() > static_cast<size_t>(mpi::kMaxDevices))
      throw Error("--device: more than " + std::to_string(mpi::kMaxDevices) + " devices");
    std::vector<RenderLane> lanes = devices->upload(*scene);
    for (size_t d = 0; d < lanes.size(); ++d) {
      // One job per device, each served alone: rank 0 shares the work out.
      jobs.push_back(std::make_unique<RenderJob>(std::vector<RenderLane>{lanes[d]}, *scene,
                                                 spec.integrator, spec.settings, spec.spectral));
      const ChunkWorker* worker = jobs.back()->integrator().chunk_worker();
      hello.devices.push_back({(*devices)[d].info().name, worker ? worker->chunk_capacity() : 0});
    }
  } catch (...) {
    hello.error = failure_text();
    hello.devices.clear();
  }
  send(mpi::kHelloTag, mpi::encode(hello));
  std::vector<std::thread> threads;
  for (size_t d = 0; d < jobs.size(); ++d)
    threads.emplace_back([&, d] {
      try {
        serve_device(static_cast<int>(d), jobs[d]->integrator());
      } catch (...) {
        // MPI itself failed: rank 0 is gone or going, and mpirun ends this rank.
      }
    });
  for (std::thread& t : threads) t.join();
  return 0;
}

}  // namespace kasha
