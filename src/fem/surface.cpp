// Boundary surface extraction (fem/surface.h). A face is on the boundary of a part when exactly one
// element of the part has it; faces are matched by their sorted corner nodes, as in the classic
// "face hashing" of unstructured-mesh codes (e.g. Löhner, Applied CFD Techniques, 2nd ed., Wiley
// 2008, §2.2 "face/edge data structures"), here with a counting sort by the smallest corner node
// (CSR buckets, one parallel pass to count and one to scatter) instead of a hash table, so that
// every bucket is a short array sorted on its own and the output does not depend on the schedule.
// Orientation: exact orient3d (Shewchuk 1997) of each face against the element's other corners.
#include "interfere/fem/surface.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>

#include "interfere/core/predicates.h"
#include "../mesh/weld_internal.h"  // ScratchBuffer
#include "surface_faces.h"
#include "surface_internal.h"

namespace interfere {

using namespace fem_detail;

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr int kShellFace = 7;                // face index of a shell's own record
constexpr std::uint8_t kDroppedShell = 0x80;  // flag of a shell that lies on a volume face

// Faces matched: a volume element's faces, or a shell as its one face.
inline ElemFaces faces_of(ElemType t) {
  if (is_shell(t)) return {1, elem_info(t).corners == 3 ? &kTriShell : &kQuadShell, elem_info(t).corners};
  return volume_faces(t);
}

template <class F>
void for_chunks(bool parallel, std::size_t n, std::size_t grain, const F& f) {
  if (parallel) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { f(r.begin(), r.end()); });
  } else if (n > 0) {
    f(std::size_t{0}, n);
  }
}

// One face occurrence, filed in the bucket of its smallest corner node: the other corners in
// increasing order (kNone as the fourth of a triangle) and element * 8 + face index.
struct FaceRec {
  std::uint32_t b, c, d, code;
};

inline void sort_key(std::uint32_t* k, int n) {
  // Sorting network for 3 or 4 values.
  auto cs = [&](int i, int j) {
    if (k[j] < k[i]) std::swap(k[i], k[j]);
  };
  if (n == 3) {
    cs(0, 1), cs(1, 2), cs(0, 1);
  } else {
    cs(0, 1), cs(2, 3), cs(0, 2), cs(1, 3), cs(1, 2);
  }
}

inline std::uint32_t min_corner(const FaceDef& f, const std::uint32_t* v) {
  std::uint32_t m = std::min(std::min(v[f.c[0]], v[f.c[1]]), v[f.c[2]]);
  return f.n == 4 ? std::min(m, v[f.c[3]]) : m;
}

// Sign vote of the face's normal against the element's corners that are not on the face:
// positive when the table order already points away from them (outward).
int outward_vote(const FaceDef& f, const std::uint32_t* v, int corners, const Vec3* p) {
  int vote = 0;
  for (int k = 0; k < corners; ++k) {
    bool on_face = false;
    for (int i = 0; i < f.n; ++i) on_face |= f.c[i] == k;
    if (on_face) continue;
    const Vec3& d = p[v[k]];
    vote += orient3d(p[v[f.c[0]]], p[v[f.c[1]]], p[v[f.c[2]]], d);
    if (f.n == 4) vote += orient3d(p[v[f.c[0]]], p[v[f.c[2]]], p[v[f.c[3]]], d);
  }
  return vote;
}

// Splits quad (q0,q1,q2,q3) (cyclic) along the shorter diagonal of the positions, the one through
// the smaller node index on a tie.
inline Tri* split_quad(std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3, const Vec3* p,
                       Tri* out) {
  const double d02 = squared_norm(p[q0] - p[q2]);
  const double d13 = squared_norm(p[q1] - p[q3]);
  const bool use02 = d02 < d13 || (d02 == d13 && std::min(q0, q2) < std::min(q1, q3));
  if (use02) {
    *out++ = {q0, q1, q2};
    *out++ = {q0, q2, q3};
  } else {
    *out++ = {q1, q2, q3};
    *out++ = {q1, q3, q0};
  }
  return out;
}

// Triangles of one face (counter-clockwise seen from outside when `flip` has made it outward).
int triangulate(const FaceDef& f, const std::uint32_t* v, FaceNodes kinds, bool subdivide, bool flip,
                const Vec3* p, Tri* out) {
  const int n = f.n;
  std::uint32_t c[4] = {0, 0, 0, 0}, m[4] = {0, 0, 0, 0}, x = 0;
  for (int i = 0; i < n; ++i) c[i] = v[f.c[i]];
  const bool quadratic = subdivide && kinds.mids;
  if (quadratic) {
    for (int i = 0; i < n; ++i) m[i] = v[f.m[i]];
    if (kinds.centre) x = v[f.centre];
  }
  if (flip) {  // (c0, c[n-1], ..., c1); mid i lies between new corners i and i+1
    std::reverse(c + 1, c + n);
    if (quadratic) std::reverse(m, m + n);
  }
  Tri* const start = out;
  if (!quadratic) {
    if (n == 3) {
      *out++ = {c[0], c[1], c[2]};
    } else {
      out = split_quad(c[0], c[1], c[2], c[3], p, out);
    }
  } else if (n == 3) {
    *out++ = {c[0], m[0], m[2]};
    *out++ = {m[0], c[1], m[1]};
    *out++ = {m[2], m[1], c[2]};
    *out++ = {m[0], m[1], m[2]};
  } else if (kinds.centre) {
    for (int i = 0; i < 4; ++i) {
      *out++ = {c[i], m[i], x};
      *out++ = {m[i], c[(i + 1) % 4], x};
    }
  } else {
    for (int i = 0; i < 4; ++i) *out++ = {c[i], m[i], m[(i + 3) % 4]};
    out = split_quad(m[0], m[1], m[2], m[3], p, out);
  }
  return static_cast<int>(out - start);
}

struct Counts {
  std::size_t boundary = 0, interior = 0, nonmanifold = 0, dropped = 0;
};

// Records with the fourth corner (quad faces) or without it (meshes whose faces are all triangles:
// 12 instead of 16 bytes per face, less memory traffic in the scatter and the bucket sort).
struct FaceRec3 {
  std::uint32_t b, c, code;
};
inline std::uint32_t fourth(const FaceRec& r) { return r.d; }
inline std::uint32_t fourth(const FaceRec3&) { return kNone; }
inline void store(FaceRec& r, const std::uint32_t* k, std::uint32_t code) { r = {k[1], k[2], k[3], code}; }
inline void store(FaceRec3& r, const std::uint32_t* k, std::uint32_t code) { r = {k[1], k[2], code}; }

// Steps 3 and 4 of extract_surface: scatter the faces into their buckets (begin[v] = end of bucket
// v on entry, its start on return), sort each bucket, flag the boundary faces and dropped shells.
template <class Rec>
Counts match_faces(const FemMesh& mesh, std::vector<std::uint64_t>& begin, const std::uint32_t* part,
                   std::vector<std::uint8_t>& flags, bool par, bool drop_shells) {
  const std::size_t ne = mesh.num_elements(), nn = mesh.num_nodes();
  // Uninitialised (the scatter writes every slot) and advised for huge pages: ~4 records of 12-16
  // bytes per tet, 48 MB for 10^6 tets, is a fresh mapping on every call (above glibc's mmap
  // threshold), and zero-filling it then faulting it in 4 KiB pages cost more than the matching.
  weld_detail::ScratchBuffer<Rec> recs(begin[nn]);
  for_chunks(par, ne, 8192, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t e = lo; e < hi; ++e) {
      const ElemFaces ef = faces_of(mesh.elem_types[e]);
      const std::uint32_t* v = mesh.element_nodes(e);
      const int shell = is_shell(mesh.elem_types[e]) ? kShellFace : 0;
      for (int f = 0; f < ef.count; ++f) {
        const FaceDef& fd = ef.faces[f];
        std::uint32_t k[4] = {v[fd.c[0]], v[fd.c[1]], v[fd.c[2]], fd.n == 4 ? v[fd.c[3]] : kNone};
        sort_key(k, fd.n);
        const std::uint64_t slot =
            std::atomic_ref<std::uint64_t>(begin[k[0]]).fetch_sub(1, std::memory_order_relaxed) - 1;
        store(recs[slot], k, static_cast<std::uint32_t>(e * 8 + (f | shell)));
      }
    }
  });
  auto match = [&](std::size_t lo, std::size_t hi) {
    Counts c;
    auto less = [&](const Rec& x, const Rec& y) {
      if (x.b != y.b) return x.b < y.b;
      if (x.c != y.c) return x.c < y.c;
      if (fourth(x) != fourth(y)) return fourth(x) < fourth(y);
      const std::uint32_t px = part[x.code >> 3], py = part[y.code >> 3];
      if (px != py) return px < py;
      return x.code < y.code;
    };
    for (std::size_t v = lo; v < hi; ++v) {
      Rec* first = recs.data() + begin[v];
      Rec* last = recs.data() + begin[v + 1];
      const std::size_t n = static_cast<std::size_t>(last - first);
      if (n == 0) continue;
      if (n <= 24) {
        for (Rec* i = first + 1; i < last; ++i) {  // insertion sort: buckets are short
          const Rec r = *i;
          Rec* j = i;
          for (; j > first && less(r, *(j - 1)); --j) *j = *(j - 1);
          *j = r;
        }
      } else {
        std::sort(first, last, less);
      }
      for (Rec* i = first; i < last;) {
        Rec* j = i + 1;
        const std::uint32_t pi = part[i->code >> 3];
        while (j < last && j->b == i->b && j->c == i->c && fourth(*j) == fourth(*i) && part[j->code >> 3] == pi) ++j;
        // Shell records are counted apart from the volume faces of the same key.
        std::size_t volumes = 0;
        const Rec* volume = nullptr;
        for (const Rec* r = i; r < j; ++r) {
          if ((r->code & 7) != kShellFace) ++volumes, volume = r;
        }
        if (volumes == 1) {
          ++c.boundary;
          std::atomic_ref<std::uint8_t>(flags[volume->code >> 3])
              .fetch_or(static_cast<std::uint8_t>(1u << (volume->code & 7)), std::memory_order_relaxed);
        } else if (volumes == 2) {
          ++c.interior;
        } else if (volumes > 2) {
          ++c.nonmanifold;
        }
        if (volumes > 0 && drop_shells) {
          for (const Rec* r = i; r < j; ++r) {
            if ((r->code & 7) != kShellFace) continue;
            ++c.dropped;
            flags[r->code >> 3] = kDroppedShell;  // a shell has one record: no other writer
          }
        }
        i = j;
      }
    }
    return c;
  };
  auto add = [](Counts a, const Counts& b) {
    a.boundary += b.boundary, a.interior += b.interior, a.nonmanifold += b.nonmanifold, a.dropped += b.dropped;
    return a;
  };
  if (!par) return match(0, nn);
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nn, 4096), Counts{},
      [&](const tbb::blocked_range<std::size_t>& r, Counts acc) { return add(acc, match(r.begin(), r.end())); },
      add);
}

Error make_error(const FemMesh& mesh, std::string reason) { return Error{.file = mesh.file, .reason = std::move(reason)}; }

}  // namespace

int element_face_count(ElemType t) { return volume_faces(t).count; }

bool part_split_from_name(const std::string& name, PartSplit& out) {
  if (name == "auto" || name == "automatic") out = PartSplit::automatic;
  else if (name == "group" || name == "by_group") out = PartSplit::by_group;
  else if (name == "connectivity") out = PartSplit::connectivity;
  else if (name == "single") out = PartSplit::single;
  else return false;
  return true;
}

Expected<SurfaceResult> extract_surface(const FemMesh& mesh, const SurfaceOptions& options) {
  const std::size_t ne = mesh.num_elements(), nn = mesh.num_nodes();
  const bool par = options.parallel;
  if (mesh.elem_ids.size() != ne || mesh.elem_groups.size() != ne || mesh.elem_offsets.size() != ne + 1 ||
      mesh.node_ids.size() != nn || mesh.elem_offsets.back() != mesh.elem_nodes.size()) {
    return make_error(mesh, "FEM mesh arrays disagree in size");
  }
  if (ne >= (std::size_t{1} << 29)) return make_error(mesh, "more than 2^29 elements");
  if (nn >= kNone) return make_error(mesh, "more than 2^32 - 1 nodes");

  // 1. Node counts and indices (the smallest bad element is named, whatever the schedule).
  std::atomic<std::size_t> bad{ne};
  for_chunks(par, ne, 8192, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t e = lo; e < hi; ++e) {
      const std::uint8_t t = static_cast<std::uint8_t>(mesh.elem_types[e]);
      bool ok = t < kNumElemTypes && mesh.elem_offsets[e + 1] >= mesh.elem_offsets[e] &&
                mesh.elem_offsets[e + 1] <= mesh.elem_nodes.size() &&
                mesh.element_size(e) == elem_info(mesh.elem_types[e]).nodes;
      if (ok) {
        const std::uint32_t* v = mesh.element_nodes(e);
        for (int k = 0, n = mesh.element_size(e); k < n; ++k) ok &= v[k] < nn;
      }
      if (!ok) {
        std::size_t cur = bad.load(std::memory_order_relaxed);
        while (e < cur && !bad.compare_exchange_weak(cur, e)) {
        }
        return;
      }
    }
  });
  if (bad.load() < ne) {
    const std::size_t e = bad.load();
    return make_error(mesh, "element " + std::to_string(mesh.elem_ids[e]) +
                                ": unknown type, wrong node count or node index out of range");
  }

  SurfaceResult result;
  PartAssignment parts = assign_parts(mesh, options.split);
  const std::uint32_t* part = parts.part.data();
  const Vec3* pos = mesh.nodes.data();

  // 2. Count the faces per smallest corner node.
  std::vector<std::uint32_t> count(nn, 0);
  for_chunks(par, ne, 8192, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t e = lo; e < hi; ++e) {
      const ElemFaces ef = faces_of(mesh.elem_types[e]);
      const std::uint32_t* v = mesh.element_nodes(e);
      for (int f = 0; f < ef.count; ++f) {
        std::atomic_ref<std::uint32_t>(count[min_corner(ef.faces[f], v)]).fetch_add(1, std::memory_order_relaxed);
      }
    }
  });
  // begin[v] starts as the end of bucket v; the scatter counts it down to the bucket's start.
  std::vector<std::uint64_t> begin(nn + 1);
  {
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < nn; ++i) begin[i] = sum += count[i];
    begin[nn] = sum;
  }
  count = {};

  // 3-4. Scatter into the buckets, sort each bucket; a (key, part) that occurs once among the volume
  // faces is a boundary face.
  bool has_quad[kNumElemTypes] = {};
  for (int t = 0; t < kNumElemTypes; ++t) {
    const ElemFaces ef = faces_of(static_cast<ElemType>(t));
    for (int f = 0; f < ef.count; ++f) has_quad[t] |= ef.faces[f].n == 4;
  }
  bool quads = false;
  for (std::size_t e = 0; e < ne && !quads; ++e) quads = has_quad[static_cast<int>(mesh.elem_types[e])];
  std::vector<std::uint8_t> flags(ne, 0);
  const Counts totals = quads ? match_faces<FaceRec>(mesh, begin, part, flags, par, options.drop_boundary_shells)
                              : match_faces<FaceRec3>(mesh, begin, part, flags, par, options.drop_boundary_shells);
  begin = {};
  result.boundary_faces = totals.boundary;
  result.interior_faces = totals.interior;
  result.nonmanifold_faces = totals.nonmanifold;
  result.dropped_shells = totals.dropped;

  // 5. Triangles in element order: count per chunk, prefix, fill.
  const bool sub = options.subdivide_quadratic;
  auto element_triangles = [&](std::size_t e) {
    const ElemType t = mesh.elem_types[e];
    const FaceNodes kinds = face_nodes(t);
    if (is_shell(t)) return flags[e] == kDroppedShell ? 0 : face_triangle_count(elem_info(t).corners, kinds, sub);
    const std::uint8_t fl = flags[e];
    if (fl == 0) return 0;
    const ElemFaces ef = volume_faces(t);
    int n = 0;
    for (int f = 0; f < ef.count; ++f) {
      if (fl >> f & 1) n += face_triangle_count(ef.faces[f].n, kinds, sub);
    }
    return n;
  };
  constexpr std::size_t kChunk = 16384;
  const std::size_t chunks = (ne + kChunk - 1) / kChunk;
  std::vector<std::size_t> chunk_begin(chunks + 1, 0);
  for_chunks(par, chunks, 1, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t c = lo; c < hi; ++c) {
      std::size_t n = 0;
      for (std::size_t e = c * kChunk, end = std::min(ne, e + kChunk); e < end; ++e) n += element_triangles(e);
      chunk_begin[c + 1] = n;
    }
  });
  std::partial_sum(chunk_begin.begin(), chunk_begin.end(), chunk_begin.begin());
  const std::size_t nt = chunk_begin[chunks];
  std::vector<Tri> tris(nt);
  std::vector<std::uint32_t> tri_elem(nt);
  std::vector<std::uint8_t> tri_face(nt), tri_flag(nt);
  std::vector<std::size_t> chunk_flipped(chunks, 0), chunk_flat(chunks, 0), chunk_skipped(chunks, 0),
      chunk_degenerate(chunks, 0);
  for_chunks(par, chunks, 1, [&](std::size_t lo, std::size_t hi) {
    Tri buf[8];
    for (std::size_t c = lo; c < hi; ++c) {
      std::size_t out = chunk_begin[c];
      for (std::size_t e = c * kChunk, end = std::min(ne, e + kChunk); e < end; ++e) {
        const ElemType t = mesh.elem_types[e];
        const std::uint32_t* v = mesh.element_nodes(e);
        const FaceNodes kinds = face_nodes(t);
        auto emit = [&](int n, std::uint8_t face, std::uint8_t flag) {
          bool degenerate = false;
          for (int i = 0; i < n; ++i, ++out) {
            tris[out] = buf[i];
            tri_elem[out] = static_cast<std::uint32_t>(e);
            tri_face[out] = face;
            tri_flag[out] = flag;
            degenerate |= collinear(pos[buf[i][0]], pos[buf[i][1]], pos[buf[i][2]]);
          }
          chunk_degenerate[c] += degenerate;
        };
        if (is_shell(t)) {
          if (flags[e] == kDroppedShell) continue;
          const FaceDef& fd = elem_info(t).corners == 3 ? kTriShell : kQuadShell;
          emit(triangulate(fd, v, kinds, sub, false, pos, buf), 1, kFlagShell);
          continue;
        }
        if (elem_info(t).dim < 2) {
          ++chunk_skipped[c];
          continue;
        }
        const std::uint8_t fl = flags[e];
        if (fl == 0) continue;
        const ElemFaces ef = volume_faces(t);
        for (int f = 0; f < ef.count; ++f) {
          if (!(fl >> f & 1)) continue;
          const int vote = outward_vote(ef.faces[f], v, ef.corners, pos);
          if (vote > 0) ++chunk_flipped[c];  // the tables list faces inward for positive elements
          if (vote == 0) ++chunk_flat[c];
          emit(triangulate(ef.faces[f], v, kinds, sub, vote < 0, pos, buf), static_cast<std::uint8_t>(f + 1), 0);
        }
      }
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) {
    result.inverted_faces += chunk_flipped[c];
    result.tied_faces += chunk_flat[c];
    result.degenerate_faces += chunk_degenerate[c];
    result.skipped_elements += chunk_skipped[c];
  }

  // 6. Split by part (stable); per part: linear faces split at the mid-side nodes of quadratic
  // neighbours, orientation by propagation and volume (surface_orient.cpp), then the part's
  // vertices in order of first use.
  const std::size_t np = parts.names.size();
  std::vector<std::size_t> part_begin(np + 1, 0);
  for (std::size_t i = 0; i < nt; ++i) ++part_begin[part[tri_elem[i]] + 1];
  std::partial_sum(part_begin.begin(), part_begin.end(), part_begin.begin());
  std::vector<std::uint32_t> order(nt);
  {
    std::vector<std::size_t> cursor(part_begin.begin(), part_begin.end() - 1);
    for (std::size_t i = 0; i < nt; ++i) order[cursor[part[tri_elem[i]]]++] = static_cast<std::uint32_t>(i);
  }
  // Quadratic elements per part (the mid-side nodes a mixed part's linear faces are split at).
  std::vector<std::vector<std::uint32_t>> quadratic(np);
  if (sub) {
    for (std::size_t e = 0; e < ne; ++e) {
      if (part[e] != kNoPart && face_nodes(mesh.elem_types[e]).mids) quadratic[part[e]].push_back(static_cast<std::uint32_t>(e));
    }
  }
  std::vector<std::uint32_t> local(nn, kNone);
  result.parts.resize(np);
  for (std::size_t p = 0; p < np; ++p) {
    SurfacePart& sp = result.parts[p];
    sp.name = parts.names[p];
    sp.group = parts.groups[p];
    const std::size_t lo = part_begin[p], hi = part_begin[p + 1];
    PartTriangles pt;
    pt.tris.resize(hi - lo), pt.elem.resize(hi - lo), pt.face.resize(hi - lo), pt.flag.resize(hi - lo);
    for (std::size_t i = lo; i < hi; ++i) {
      const std::uint32_t t = order[i];
      pt.tris[i - lo] = tris[t], pt.elem[i - lo] = tri_elem[t], pt.face[i - lo] = tri_face[t];
      pt.flag[i - lo] = tri_flag[t];
    }
    if (!quadratic[p].empty()) result.split_faces += split_at_mid_nodes(mesh, quadratic[p], pt);
    const OrientStats os = orient_part(mesh, pt, par);
    result.reoriented_triangles += os.reoriented;
    sp.components = os.components;
    sp.open_components = os.open_components;
    sp.degenerate_components = os.degenerate_components;
    sp.nonorientable_components = os.nonorientable_components;
    sp.enclosed_volume = os.volume;
    const std::size_t pn = pt.tris.size();
    sp.mesh.triangles.resize(pn);
    sp.tri_element = std::move(pt.elem);
    sp.tri_face = std::move(pt.face);
    for (std::size_t i = 0; i < pn; ++i) {
      Tri out;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t& l = local[pt.tris[i][k]];
        if (l == kNone) {
          l = static_cast<std::uint32_t>(sp.vertex_node.size());
          sp.vertex_node.push_back(pt.tris[i][k]);
        }
        out[k] = l;
      }
      sp.mesh.triangles[i] = out;
    }
    sp.mesh.positions.resize(sp.vertex_node.size());
    for (std::size_t i = 0; i < sp.vertex_node.size(); ++i) {
      sp.mesh.positions[i] = pos[sp.vertex_node[i]];
      local[sp.vertex_node[i]] = kNone;
    }
  }
  for (std::size_t e = 0; e < ne; ++e) {
    if (part[e] == kNoPart) continue;
    if (!is_shell(mesh.elem_types[e])) {
      ++result.parts[part[e]].volume_elements;
    } else if (flags[e] != kDroppedShell) {
      ++result.parts[part[e]].shell_elements;
    }
  }
  return result;
}

}  // namespace interfere
