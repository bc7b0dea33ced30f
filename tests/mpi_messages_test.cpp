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
  p.tallies = {{"rejected samples", 2}, {"time: host (s)", 0.015625}};
  p.kept = [] { return std::vector<float>{1}; };  // stays behind: only rank 0 keeps an image
  const mpi::Reply back = mpi::decode_reply(mpi::encode(reply));
  ASSERT_EQ(back.kind, mpi::Kind::result);
  EXPECT_EQ(back.result.pass, 7);
  EXPECT_EQ(back.result.samples, 3);
  EXPECT_EQ(back.result.pixel_samples, p.pixel_samples);
  EXPECT_TRUE(same_bits(back.result.sums, p.sums));
  EXPECT_TRUE(std::signbit(back.result.sums[3]));
  EXPECT_EQ(back.result.fraction, 0.625);
  EXPECT_EQ(back.result.tallies, p.tallies);
  EXPECT_FALSE(back.result.kept);
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
  const mpi::Reply back = mpi::decode_reply(mpi::encode(reply));
  ASSERT_EQ(back.kind, mpi::Kind::chunk_result);
  EXPECT_TRUE(same_bits(back.chunk.flux, c.flux));
  EXPECT_EQ(back.chunk.found, c.found);
  EXPECT_EQ(back.chunk.traced, 32768);
  EXPECT_EQ(back.chunk.records, 131000);
  EXPECT_EQ(back.chunk.per_photon, 4.5);
  EXPECT_EQ(back.chunk.overflows, 1);

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
