#pragma once
// A scene of object instances (docs/formats.md#instances) and the same scene with every
// placement written out as shapes: what the instancing tests compare.
#include <string>

namespace kasha::test {

// Written to the tests' scratch folder; returns its path. An object of a torus and a sphere is
// placed 9 times (rotated, scaled unevenly, one mirrored), a second object once, in an inward
// box lit by a ceiling lamp. `flattened`: the same placements as the scene's own shapes.
std::string instanced_scene(bool flattened);

}  // namespace kasha::test
