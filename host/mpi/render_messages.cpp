#include "mpi/render_messages.h"

#include "core/error.h"
#include "mpi/message.h"

namespace kasha::mpi {

namespace {
Kind kind_of(MessageReader& in) {
  return static_cast<Kind>(in.get<char>());
}

Error unexpected(const char* what, Kind kind) {
  return Error(std::string("MPI: a ") + what + " message of unknown kind '" +
               static_cast<char>(kind) + "' (ranks running different kasha builds?)");
}

// A pass's counters: every number field in declaration order, then the devices' work and the
// stages' times (get_counters reads them in the same order).
void put_counters(MessageWriter& out, const PassCounters& c) {
  out.put(c.rejected_samples).put(c.power_emitted_w).put(c.power_absorbed_w);
  out.put(c.power_escaped_w).put(c.power_in_flight_w).put(c.depth_guard.cut);
  out.put(c.depth_guard.of).put(c.camera_depth_guard.cut).put(c.camera_depth_guard.of);
  out.put(c.closest_rays).put(c.shadow_rays).put(c.gather_queries).put(c.photons_stored);
  out.put(c.photon_store_overflows).put(c.light_vertices_stored).put(c.light_chunks);
  out.put(c.merging_radius).put(c.device_work).put<uint64_t>(c.stage_seconds.size());
  for (const StageTime& s : c.stage_seconds) out.put(s.stage).put(s.seconds);
}

PassCounters get_counters(MessageReader& in) {
  PassCounters c;
  for (double* v : {&c.rejected_samples, &c.power_emitted_w, &c.power_absorbed_w,
                    &c.power_escaped_w, &c.power_in_flight_w, &c.depth_guard.cut, &c.depth_guard.of,
                    &c.camera_depth_guard.cut, &c.camera_depth_guard.of, &c.closest_rays,
                    &c.shadow_rays, &c.gather_queries, &c.photons_stored, &c.photon_store_overflows,
                    &c.light_vertices_stored, &c.light_chunks, &c.merging_radius})
    *v = in.get<double>();
  c.device_work = in.get_vector<double>();
  for (uint64_t n = in.get<uint64_t>(); n > 0; --n) {
    StageTime s;
    s.stage = in.get_string();
    s.seconds = in.get<double>();
    c.stage_seconds.push_back(s);
  }
  return c;
}
}  // namespace

std::vector<char> encode(const Request& r) {
  MessageWriter out;
  out.put(static_cast<char>(r.kind)).put(r.pass).put(r.first).put(r.count).put(r.seconds_left);
  out.put(static_cast<uint8_t>(r.interrupted));
  if (r.kind == Kind::inputs)
    out.put(r.inputs.visible_points).put(r.inputs.radius).put(r.inputs.cell);
  return out.take();
}

Request decode_request(const std::vector<char>& bytes) {
  MessageReader in(bytes);
  Request r;
  r.kind = kind_of(in);
  if (r.kind != Kind::pass && r.kind != Kind::inputs && r.kind != Kind::chunk)
    throw unexpected("request", r.kind);
  r.pass = in.get<int>();
  r.first = in.get<uint64_t>();
  r.count = in.get<uint64_t>();
  r.seconds_left = in.get<double>();
  r.interrupted = in.get<uint8_t>() != 0;
  if (r.kind == Kind::inputs) {
    r.inputs.visible_points = in.get_vector<float>();
    r.inputs.radius = in.get_vector<float>();
    r.inputs.cell = in.get_vector<float>();
  }
  in.end();
  return r;
}

std::vector<char> encode(const Reply& r) {
  MessageWriter out;
  out.put(static_cast<char>(r.kind));
  switch (r.kind) {
    case Kind::result: {
      const PassResult& p = r.result;
      out.put(p.pass).put(p.samples).put(p.pixel_samples).put(p.sums).put(p.fraction);
      put_counters(out, p.counters);
      break;
    }
    case Kind::chunk_result: {
      const ChunkResult& c = r.chunk;
      out.put(c.flux).put(c.found).put(c.traced).put(c.records).put(c.cut).put(c.trace_s);
      out.put(c.gather_s).put(c.overflows).put(c.per_photon).put(c.gathers).put(c.closest_rays);
      out.put(c.shadow_rays).put(c.work);
      break;
    }
    default:
      out.put(r.error);
  }
  return out.take();
}

Reply decode_reply(const std::vector<char>& bytes) {
  MessageReader in(bytes);
  Reply r;
  r.kind = kind_of(in);
  switch (r.kind) {
    case Kind::result: {
      PassResult& p = r.result;
      p.pass = in.get<int>();
      p.samples = in.get<long long>();
      p.pixel_samples = in.get_vector<long long>();
      p.sums = in.get_vector<double>();
      p.fraction = in.get<double>();
      p.counters = get_counters(in);
      break;
    }
    case Kind::chunk_result: {
      ChunkResult& c = r.chunk;
      c.flux = in.get_vector<double>();
      c.found = in.get_vector<int>();
      for (double* v : {&c.traced, &c.records, &c.cut, &c.trace_s, &c.gather_s, &c.overflows,
                        &c.per_photon, &c.gathers, &c.closest_rays, &c.shadow_rays})
        *v = in.get<double>();
      c.work = in.get_vector<double>();
      break;
    }
    case Kind::error:
      r.error = in.get_string();
      break;
    default:
      throw unexpected("reply", r.kind);
  }
  in.end();
  return r;
}

std::vector<char> encode(const Hello& h) {
  MessageWriter out;
  out.put(static_cast<char>(h.error.empty() ? Kind::hello : Kind::error));
  if (!h.error.empty()) return out.put(h.error).take();
  out.put(h.render).put<uint64_t>(h.devices.size());
  for (const RemoteDevice& d : h.devices) out.put(d.name).put(d.capacity);
  return out.take();
}

Hello decode_hello(const std::vector<char>& bytes) {
  MessageReader in(bytes);
  Hello h;
  const Kind kind = kind_of(in);
  if (kind == Kind::error) {
    h.error = in.get_string();
  } else if (kind == Kind::hello) {
    h.render = in.get_string();
    for (uint64_t n = in.get<uint64_t>(); n > 0; --n) {
      RemoteDevice d;
      d.name = in.get_string();
      d.capacity = in.get<uint64_t>();
      h.devices.push_back(d);
    }
  } else {
    throw unexpected("hello", kind);
  }
  in.end();
  return h;
}

double seconds_left(const PassControl& control) {
  if (!control.deadline) return -1;
  return std::max(
      0.0, std::chrono::duration<double>(*control.deadline - PassControl::Clock::now()).count());
}

PassControl control_for(double seconds_left) {
  PassControl control;
  if (seconds_left >= 0)
    control.deadline =
        PassControl::Clock::now() + std::chrono::duration_cast<PassControl::Clock::duration>(
                                        std::chrono::duration<double>(seconds_left));
  return control;
}

}  // namespace kasha::mpi
