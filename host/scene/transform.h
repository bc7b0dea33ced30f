#pragma once
// Shape transforms: {"translate": [x,y,z], "rotate": {"axis": [..], "deg": a}, "scale": s |
// [sx,sy,sz]} applied as scale, then rotate, then translate; or {"matrix": [16 numbers, row-major]}
// alone.
#include <Eigen/Geometry>

#include "core/json_node.h"

namespace kasha {

Eigen::Affine3d parse_transform(const JsonNode& node);

}  // namespace kasha
