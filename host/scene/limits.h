#pragma once
// The ranges scene input must stay inside so that float kernels and Embree can carry it; checked
// when the scene loads, where the file, JSON path or line is still known.

namespace kasha {

// The largest coordinate a vertex or the camera may have (after transforms): squared distances
// stay far inside float, and Embree asserts on non-finite bounds.
constexpr double kMaxCoordinate = 1e18;
// The largest power (W) one emitter may send: light-sampling weights are power ratios and sums of
// it, and the kernels' estimates carry it in float.
constexpr double kMaxEmitterPower = 1e35;
// The largest light-sampling density per unit area (float, like the kernels read it).
constexpr double kMaxAreaDensity = 1e30;

}  // namespace kasha
