// MAVLink codec throughput (docs/swath-fleet.md: >= 1 M frames/s): the stream parser on a capture
// of random frames of all 23 messages (with MAVLink 1 frames and 5 % noise between frames), fed in
// 1,400-byte datagrams; and packing + serializing a GLOBAL_POSITION_INT.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "mavlink_test_support.hpp"
#include "swath/mavlink/frame.hpp"
#include "swath/mavlink/messages.hpp"

namespace {

using namespace swath::mavlink;

std::vector<std::uint8_t> random_stream(std::size_t frames, std::size_t* noise_bytes) {
  std::mt19937_64 rng(42);
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i < frames; ++i) {
    if (rng() % 20 == 0) {
      for (int k = 0; k < 8; ++k) out.push_back(static_cast<std::uint8_t>(rng()));
      *noise_bytes += 8;
    }
    const auto b = serialize(test::random_frame(rng, static_cast<std::uint8_t>(i)));
    out.insert(out.end(), b.begin(), b.end());
  }
  return out;
}

void BM_ParseStream(benchmark::State& state) {
  std::size_t noise = 0;
  const std::vector<std::uint8_t> stream = random_stream(10000, &noise);
  std::uint64_t frames = 0;
  for (auto _ : state) {
    FrameParser parser;
    for (std::size_t at = 0; at < stream.size(); at += 1400) {
      parser.feed({stream.data() + at, std::min<std::size_t>(1400, stream.size() - at)});
      for (Frame f; parser.next(f);) {
        benchmark::DoNotOptimize(f.payload[0]);
        ++frames;
      }
    }
  }
  state.counters["frames_per_s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
  state.counters["MB_per_s"] = benchmark::Counter(
      double(stream.size()) * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParseStream)->Unit(benchmark::kMillisecond);

void BM_PackSerializePosition(benchmark::State& state) {
  GlobalPositionInt g{.time_boot_ms = 123456,
                      .lat_degE7 = 473977420,
                      .lon_degE7 = 85455940,
                      .alt_mm = 488000,
                      .relative_alt_mm = 30000,
                      .vx_cm_s = 120,
                      .vy_cm_s = -40,
                      .vz_cm_s = 3,
                      .hdg_cdeg = 9000};
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  const std::uint8_t extra = find_message(GlobalPositionInt::kId)->crc_extra;
  for (auto _ : state) {
    ++g.time_boot_ms;
    benchmark::DoNotOptimize(serialize(pack(g, {1, 1, 1}), extra, out.data()));
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PackSerializePosition);

}  // namespace

BENCHMARK_MAIN();
