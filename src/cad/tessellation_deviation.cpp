// Measured chordal deviation of a face's tessellation (cad/model.h, Part::tessellation_deviation):
// BRepMesh_IncrementalMesh refines until the deflection it checks lies within the linear
// deflection asked for; this measures the result afterwards, so a report can say what the
// triangles really are. At each triangle's centroid and edge midpoints, the distance from the
// point on the triangle to the face's (untrimmed) surface is bounded from above twice: by the
// surface point of the same (u, v) (the triangulation's UV nodes, Poly_Triangulation::UVNode;
// cheap, but loose where the parametrisation is uneven: near a cone's apex or on a trimmed
// B-spline it overstates the distance up to 50 times on NIST test parts), and, where that exceeds
// `threshold`, by the nearest point GeomAPI_ProjectPointOnSurf finds (Extrema). The smaller one is
// kept: every sample's value is the distance to a point of the surface, at least the true
// distance; the result is a sampled measure (between samples the triangle may lie farther), not
// a bound.
#ifndef OCC_CONVERT_SIGNALS
#define OCC_CONVERT_SIGNALS
#endif
#include <BRepAdaptor_Surface.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Surface.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopoDS_Face.hxx>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "occt_internal.h"

namespace interfere::cad::detail {

double tessellation_deviation(const TopoDS_Face& face, const Poly_Triangulation& tri, const gp_Trsf& to_world,
                              double threshold) {
  if (!tri.HasUVNodes()) return -1;
  // In parallel over ranges of triangles (issue #29: the casing's B-spline wall holds 27,000 of its
  // 35,500 triangles, measured after BRepMesh on one thread), each range with its own adaptor (its
  // B-spline evaluation cache is not shared) and surface. A range projects a sample only above its
  // own running maximum, so ranges project more samples than one pass would; the maximum is the
  // same: it is the largest of min(same-(u, v) distance, projection) over the samples above the
  // threshold and the same-(u, v) distances below it, whichever of them were projected (a sample not
  // projected lies at or under a value already counted).
  const auto range_worst = [&](int first, int last) {
    const BRepAdaptor_Surface surface(face, false);  // (global coordinates: the face's location applied)
    Handle(Geom_Surface) geometry;                   // for projections, made when first needed
    double worst = 0;
    for (int t = first; t < last; ++t) {
      int n[3];
      tri.Triangle(t).Get(n[0], n[1], n[2]);
      std::array<gp_Pnt, 3> p;
      std::array<gp_Pnt2d, 3> uv;
      for (int k = 0; k < 3; ++k) {
        p[k] = tri.Node(n[k]).Transformed(to_world);
        uv[k] = tri.UVNode(n[k]);
      }
      // (weights of the three corners) for the centroid and the three edge midpoints
      static constexpr double kSamples[4][3] = {
          {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
      for (const auto& w : kSamples) {
        double x = 0, y = 0, z = 0, u = 0, v = 0;
        for (int k = 0; k < 3; ++k) {
          x += w[k] * p[k].X(), y += w[k] * p[k].Y(), z += w[k] * p[k].Z();
          u += w[k] * uv[k].X(), v += w[k] * uv[k].Y();
        }
        const gp_Pnt q(x, y, z);
        double d = surface.Value(u, v).Distance(q);
        if (d > threshold && d > worst) {
          try {  // (a projection that fails keeps the same-(u, v) distance, an upper estimate too)
            OCC_CATCH_SIGNALS
            if (geometry.IsNull()) geometry = BRep_Tool::Surface(face);  // (located)
            const GeomAPI_ProjectPointOnSurf projection(q, geometry);
            if (projection.IsDone() && projection.NbPoints() > 0) d = std::min(d, projection.LowerDistance());
          } catch (const Standard_Failure&) {
          }
        }
        worst = std::max(worst, d);
      }
    }
    return worst;
  };
  const int nt = tri.NbTriangles();
  constexpr int kSerial = 2048;  // (small faces: one range, no task overhead)
  if (nt <= kSerial) return range_worst(1, nt + 1);
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(1, nt + 1, 1024), 0.0,
      [&](const tbb::blocked_range<int>& r, double m) { return std::max(m, range_worst(r.begin(), r.end())); },
      [](double a, double b) { return std::max(a, b); });
}

}  // namespace interfere::cad::detail
