// Closed triangle meshes of implicit surfaces: marching tetrahedra over a grid split into Kuhn
// tetrahedra (six per cell around its main diagonal, matching across cell faces), so the
// surface {f = 0} comes out watertight, manifold and oriented outwards (towards f > 0).
#pragma once
#include <functional>

#include "core/bvh.hpp"
#include "core/mesh_build.hpp"

namespace vdc {

// The surface f = 0 of a field negative inside, sampled on a grid of spacing h over `box` (which
// must contain the inside with at least one cell to spare). Vertices sit on grid edges at the
// linear zero of f, kept at least 5% of the edge from its ends so that no triangle is degenerate.
// Faces are counter-clockwise seen from outside; uvs are empty.
MeshSource polygonize(const std::function<double(const Vec3&)>& f, const Aabb& box, double h);

}  // namespace vdc
