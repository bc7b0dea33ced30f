// The MPI messages (mpi/render_messages.h) without MPI: what is encoded decodes to the same
// values, every double bit for bit, and a short or overlong message fails loudly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "mpi/render_messages.h"

using namespace kasha;

namespace {

// Every counter a value of its own (i + k for field k), two devices' work and two stages.
PassCounters distinct(double i) {
  PassCounters c;
  double k = 0;
  for (double* v : {&c.rejected_samples, &c.power_emitted_w, &c.power_absorbed_w,
                    &c.power_escaped_w, &c.power_in_flight_w, &c.depth_guard.cut, &c.depth_guard.of,
                    &c.camera_depth_guard.cut, &c.camera_depth_guard.of, &c.closest_rays,
                    &c.shadow_rays, &c.gather_queries, &c.photons_stored, &c.photon_store_overflows,
                    &c.light_vertices_stored, &c.light_chunks, &c.merging_radius})
    *v = i + k++;
  c.device_work = {i + 100, i + 101};
  c.add_stage("light pass", i + 200);
  c.add_stage("grid", i + 201);
  return c;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST(MpiMessages, PassResultKeepsEveryBit) {
  mpi::Reply reply;
  reply.kind = mpi::Kind::result;
  PassResult& p = reply.result;
  p.pass = 7;
  p.samples = 3;
  p.pixel_samples = {3, 4, 5};
  // Values whose decimal printing would lose bits, a denormal and a negative zero.
  p.sums = {0.1, 1.0 / 3.0, std::numeric_limits<double>::denorm_min(), -0.0, 1e300};
  p.fraction = 0.625;
  p.counters.rejected_samples = 2;
  p.counters.add_stage("host", 0.015625);
  p.kept = [] { return std::vector<float>{1}; };  // stays behind: only rank 0 keeps an image
  const mpi::Reply back = mpi::decode_reply(mpi::encode(reply));
  ASSERT_EQ(back.kind, mpi::Kind::result);
  EXPECT_EQ(back.result.pass, 7);
  EXPECT_EQ(back.result.samples, 3);
  EXPECT_EQ(back.result.pixel_samples, p.pixel_samples);
  EXPECT_TRUE(same_bits(back.result.sums, p.sums));
  EXPECT_TRUE(std::signbit(back.result.sums[3]));
  EXPECT_EQ(back.result.fraction, 0.625);
  EXPECT_EQ(back.result.counters.rejected_samples, 2);
  ASSERT_EQ(back.result.counters.stage_seconds.size(), 1u);
  EXPECT_EQ(back.result.counters.stage_seconds[0].stage, "host");
  EXPECT_EQ(back.result.counters.stage_seconds[0].seconds, 0.015625);
  EXPECT_FALSE(back.result.kept);
}

// Each counter travels to rank 0 and adds over passes as its comment in film/pass_counters.h says
// (every one adds; devices and stages add per device and per stage), none dropped on the way.
TEST(MpiMessages, PassCountersTravelAndAddFieldByField) {
  static_assert(sizeof(PassCounters) == 17 * sizeof(double) + 2 * sizeof(std::vector<double>),
                "a new counter: give it a value in distinct() and check it here");
  mpi::Reply reply;
  reply.kind = mpi::Kind::result;
  reply.result.counters = distinct(1000);
  PassCounters film = distinct(0);
  film.device_work.resize(1);  // a device that did no work in the first pass
  film.stage_seconds.erase(film.stage_seconds.begin());  // "grid" first timed in the second
  film.add(mpi::decode_reply(mpi::encode(reply)).result.counters);
  const PassCounters& c = film;
  double k = 0;
  for (double v :
       {c.rejected_samples, c.power_emitted_w, c.power_absorbed_w, c.power_escaped_w,
        c.power_in_flight_w, c.depth_guard.cut, c.depth_guard.of, c.camera_depth_guard.cut,
        c.camera_depth_guard.of, c.closest_rays, c.shadow_rays, c.gather_queries, c.photons_stored,
        c.photon_store_overflows, c.light_vertices_stored, c.light_chunks, c.merging_radius}) {
    EXPECT_EQ(v, 1000 + 2 * k) << "counter " << k;
    ++k;
  }
  EXPECT_EQ(c.device_work, std::vector<double>({1200, 1101}));
  ASSERT_EQ(c.stage_seconds.size(), 2u);  // in name order, as `render` prints them
  EXPECT_EQ(c.stage_seconds[0].stage, "grid");
  EXPECT_EQ(c.stage_seconds[0].seconds, 1201);
  EXPECT_EQ(c.stage_seconds[1].stage, "light pass");
  EXPECT_EQ(c.stage_seconds[1].seconds, 1400);
  EXPECT_EQ(c.work_of(1), 1101);
  EXPECT_EQ(c.work_of(2), 0);
}

TEST(MpiMessages, ChunkResultAndInputsRoundTrip) {
  mpi::Reply reply;
  reply.kind = mpi::Kind::chunk_result;
  ChunkResult& c = reply.chunk;
  c.flux = {0.1, 0.2, 0.30000000000000004};
  c.found = {1, 0, 9};
  c.traced = 32768;
  c.records = 131000;
  c.cut = 0.5;
  c.trace_s = 0.25;
  c.gather_s = 0.125;
  c.overflows = 1;
  c.per_photon = 4.5;
  c.work = {30000, 2768};
  const mpi::Reply back = mpi::decode_reply(mpi::encode(reply));
  ASSERT_EQ(back.kind, mpi::Kind::chunk_result);
  EXPECT_TRUE(same_bits(back.chunk.flux, c.flux));
  EXPECT_EQ(back.chunk.found, c.found);
  EXPECT_EQ(back.chunk.traced, 32768);
  EXPECT_EQ(back.chunk.records, 131000);
  EXPECT_EQ(back.chunk.per_photon, 4.5);
  EXPECT_EQ(back.chunk.overflows, 1);
  EXPECT_EQ(back.chunk.work, c.work);

  mpi::Request request;
  request.kind = mpi::Kind::inputs;
  request.seconds_left = 2.5;
  request.interrupted = true;
  request.inputs.visible_points = {1.5f, -2.0f, 3.25f};
  request.inputs.radius = {0.01f};
  request.inputs.cell = {0.02f, 0.0f};
  const mpi::Request in = mpi::decode_request(mpi::encode(request));
  EXPECT_EQ(in.kind, mpi::Kind::inputs);
  EXPECT_EQ(in.seconds_left, 2.5);
  EXPECT_TRUE(in.interrupted);
  EXPECT_EQ(in.inputs.visible_points, request.inputs.visible_points);
  EXPECT_EQ(in.inputs.radius, request.inputs.radius);
  EXPECT_EQ(in.inputs.cell, request.inputs.cell);

  request = mpi::Request{};
  request.kind = mpi::Kind::chunk;
  request.pass = 4;
  request.first = 1ull << 33;
  request.count = 32768;
  const mpi::Request chunk = mpi::decode_request(mpi::encode(request));
  EXPECT_EQ(chunk.pass, 4);
  EXPECT_EQ(chunk.first, 1ull << 33);
  EXPECT_EQ(chunk.count, 32768u);
  EXPECT_TRUE(chunk.inputs.visible_points.empty());
}

TEST(MpiMessages, HelloCarriesDevicesOrTheFailure) {
  mpi::Hello hello;
  hello.devices = {{"GPU one", 1u << 20}, {"CPU", 0}};
  hello.render = "scene.json|photon|1";
  mpi::Hello back = mpi::decode_hello(mpi::encode(hello));
  EXPECT_EQ(back.render, "scene.json|photon|1");
  ASSERT_EQ(back.devices.size(), 2u);
  EXPECT_EQ(back.devices[0].name, "GPU one");
  EXPECT_EQ(back.devices[0].capacity, 1u << 20);
  EXPECT_TRUE(back.error.empty());
  hello = mpi::Hello{};
  hello.error = "scene.json: cannot open file";
  back = mpi::decode_hello(mpi::encode(hello));
  EXPECT_EQ(back.error, "scene.json: cannot open file");
  EXPECT_TRUE(back.devices.empty());
}

TEST(MpiMessages, ShortOrOverlongMessagesFail) {
  mpi::Reply reply;
  reply.kind = mpi::Kind::result;
  reply.result.sums.assign(100, 1.0);
  std::vector<char> bytes = mpi::encode(reply);
  std::vector<char> shorter(bytes.begin(), bytes.end() - 1);
  EXPECT_THROW(mpi::decode_reply(shorter), Error);
  bytes.push_back(0);
  EXPECT_THROW(mpi::decode_reply(bytes), Error);
  EXPECT_THROW(mpi::decode_reply({}), Error);
  EXPECT_THROW(mpi::decode_request({'Z'}), Error);
}

TEST(MpiMessages, DeadlinesTravelAsSecondsLeft) {
  PassControl none;
  EXPECT_LT(mpi::seconds_left(none), 0);
  EXPECT_FALSE(mpi::control_for(-1).deadline);
  PassControl soon = mpi::control_for(30);
  ASSERT_TRUE(soon.deadline);
  EXPECT_NEAR(mpi::seconds_left(soon), 30, 1);
  EXPECT_EQ(mpi::seconds_left(mpi::control_for(0)), 0);
}
