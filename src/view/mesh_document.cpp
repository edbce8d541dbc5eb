// Meshes with per-triangle labels as a viewer document (view/mesh_document.h).
#include "interfere/view/mesh_document.h"

#include <array>

namespace interfere::view {

Rgb label_color(std::size_t i) {
  // Tableau-like categorical colours, then golden-angle hues for more labels.
  static constexpr std::array<Rgb, 10> kBase{{{0.12f, 0.47f, 0.71f}, {1.00f, 0.50f, 0.05f}, {0.17f, 0.63f, 0.17f},
                                              {0.58f, 0.40f, 0.74f}, {0.55f, 0.34f, 0.29f}, {0.89f, 0.47f, 0.76f},
                                              {0.74f, 0.74f, 0.13f}, {0.09f, 0.75f, 0.81f}, {0.50f, 0.50f, 0.50f},
                                              {0.84f, 0.15f, 0.16f}}};
  if (i < kBase.size()) return kBase[i];
  const double h = static_cast<double>(i) * 0.6180339887498949;
  const double f = h - static_cast<double>(static_cast<long long>(h));
  // HSV (f, 0.6, 0.85) to RGB
  const double s = 0.6, v = 0.85, h6 = f * 6;
  const int k = static_cast<int>(h6) % 6;
  const double fr = h6 - static_cast<int>(h6), p = v * (1 - s), q = v * (1 - s * fr), t = v * (1 - s * (1 - fr));
  const std::array<std::array<double, 3>, 6> rgb{{{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}}};
  return {static_cast<float>(rgb[k][0]), static_cast<float>(rgb[k][1]), static_cast<float>(rgb[k][2])};
}

Document meshes_document(std::string title, std::vector<MeshLayer> layers, std::vector<LegendEntry> legend) {
  Document doc;
  doc.title = std::move(title);
  doc.legend = std::move(legend);
  bool any_labels = false;
  for (const MeshLayer& l : layers) any_labels = any_labels || !l.labels.empty();
  for (MeshLayer& l : layers) {
    ViewMesh m;
    m.source_triangles = l.mesh.num_triangles();
    if (any_labels) {
      // Unlabelled triangles: an entry of the layer's own colour, so every triangle has a colour.
      const auto other = static_cast<std::uint32_t>(doc.legend.size());
      doc.legend.push_back({l.name + " (other faces)", l.color});
      m.face_colors.assign(l.mesh.num_triangles(), other);
      for (std::size_t t = 0; t < l.labels.size() && t < m.face_colors.size(); ++t)
        if (l.labels[t] != kNoLabel) m.face_colors[t] = l.labels[t];
    }
    m.mesh = std::move(l.mesh);
    doc.meshes.push_back(std::move(m));
    ViewBody b;
    b.id = l.id, b.name = l.name, b.path = l.path.empty() ? "/" + l.name : l.path, b.role = l.role;
    b.mesh = static_cast<std::uint32_t>(doc.meshes.size() - 1);
    b.pose = l.pose, b.visible = l.visible, b.color = l.color;
    doc.bodies.push_back(std::move(b));
  }
  return doc;
}

}  // namespace interfere::view
