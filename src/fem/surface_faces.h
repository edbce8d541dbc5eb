// Face tables of the volume elements (Abaqus/CalculiX face numbering, VTK node order; see
// include/interfere/fem/surface.h) and the triangulation of one face. Internal to src/fem.
#pragma once
#include <array>
#include <cstdint>

#include "interfere/fem/fem_mesh.h"

namespace interfere::fem_detail {

inline constexpr std::uint8_t kNo = 255;

/// One face: `n` corners (3 or 4) in the table's cyclic order, mids[i] the mid-side node between
/// corners i and i+1 (quadratic elements), centre the face-centre node (hex27) or kNo.
struct FaceDef {
  std::uint8_t n;
  std::array<std::uint8_t, 4> c;
  std::array<std::uint8_t, 4> m;
  std::uint8_t centre;
};

struct ElemFaces {
  int count = 0;
  const FaceDef* faces = nullptr;
  int corners = 0;  ///< corner nodes of the element (the opposite-corner vote uses them)
};

inline constexpr FaceDef kTetFaces[4] = {
    {3, {0, 1, 2, 0}, {4, 5, 6, kNo}, kNo},
    {3, {0, 3, 1, 0}, {7, 8, 4, kNo}, kNo},
    {3, {1, 3, 2, 0}, {8, 9, 5, kNo}, kNo},
    {3, {2, 3, 0, 0}, {9, 7, 6, kNo}, kNo},
};
inline constexpr FaceDef kHexFaces[6] = {
    {4, {0, 1, 2, 3}, {8, 9, 10, 11}, 24},
    {4, {4, 7, 6, 5}, {15, 14, 13, 12}, 25},
    {4, {0, 4, 5, 1}, {16, 12, 17, 8}, 22},
    {4, {1, 5, 6, 2}, {17, 13, 18, 9}, 21},
    {4, {2, 6, 7, 3}, {18, 14, 19, 10}, 23},
    {4, {3, 7, 4, 0}, {19, 15, 16, 11}, 20},
};
inline constexpr FaceDef kWedgeFaces[5] = {
    {3, {0, 1, 2, 0}, {6, 7, 8, kNo}, kNo},
    {3, {3, 5, 4, 0}, {11, 10, 9, kNo}, kNo},
    {4, {0, 3, 4, 1}, {12, 9, 13, 6}, kNo},
    {4, {1, 4, 5, 2}, {13, 10, 14, 7}, kNo},
    {4, {2, 5, 3, 0}, {14, 11, 12, 8}, kNo},
};
inline constexpr FaceDef kPyrFaces[5] = {
    {4, {0, 1, 2, 3}, {5, 6, 7, 8}, kNo},
    {3, {0, 4, 1, 0}, {9, 10, 5, kNo}, kNo},
    {3, {1, 4, 2, 0}, {10, 11, 6, kNo}, kNo},
    {3, {2, 4, 3, 0}, {11, 12, 7, kNo}, kNo},
    {3, {3, 4, 0, 0}, {12, 9, 8, kNo}, kNo},
};
// Shells: the element is its own face.
inline constexpr FaceDef kTriShell = {3, {0, 1, 2, 0}, {3, 4, 5, kNo}, kNo};
inline constexpr FaceDef kQuadShell = {4, {0, 1, 2, 3}, {4, 5, 6, 7}, 8};

inline ElemFaces volume_faces(ElemType t) {
  switch (t) {
    case ElemType::tet4:
    case ElemType::tet10: return {4, kTetFaces, 4};
    case ElemType::pyr5:
    case ElemType::pyr13: return {5, kPyrFaces, 5};
    case ElemType::wedge6:
    case ElemType::wedge15: return {5, kWedgeFaces, 6};
    case ElemType::hex8:
    case ElemType::hex20:
    case ElemType::hex27: return {6, kHexFaces, 8};
    default: return {};
  }
}

inline bool is_shell(ElemType t) {
  return t == ElemType::tri3 || t == ElemType::tri6 || t == ElemType::quad4 || t == ElemType::quad8 ||
         t == ElemType::quad9;
}

/// Which node kinds a face of element type t has: mid-side nodes, centre node.
struct FaceNodes {
  bool mids = false, centre = false;
};
inline FaceNodes face_nodes(ElemType t) {
  switch (t) {
    case ElemType::tri6: case ElemType::quad8: case ElemType::tet10: case ElemType::pyr13:
    case ElemType::wedge15: case ElemType::hex20: return {true, false};
    case ElemType::quad9: case ElemType::hex27: return {true, true};
    default: return {};
  }
}

/// Triangles a face becomes.
inline int face_triangle_count(int corners, FaceNodes k, bool subdivide) {
  if (!subdivide || !k.mids) return corners == 3 ? 1 : 2;
  if (corners == 3) return 4;
  return k.centre ? 8 : 6;
}

}  // namespace interfere::fem_detail
