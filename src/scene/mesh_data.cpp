#include "scene/mesh_data.h"

#include <cmath>
#include <unordered_map>

namespace tuneray {

void MeshData::append(const MeshData& other) {
  auto base = static_cast<uint32_t>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  for (const Triangle& t : other.triangles)
    triangles.push_back({{t.v[0] + base, t.v[1] + base, t.v[2] + base}});
}

MeshData make_quad(Vec3f corner, Vec3f u, Vec3f v, Vec3f facing) {
  if (dot(cross(u, v), facing) < 0) std::swap(u, v);
  Vec3f n = normalize(cross(u, v));
  MeshData m;
  m.positions = {corner, corner + u, corner + u + v, corner + v};
  m.normals.assign(4, n);
  m.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  return m;
}

MeshData make_box(Vec3f lo, Vec3f hi) {
  Vec3f e = hi - lo;
  Vec3f ex(e.x, 0, 0), ey(0, e.y, 0), ez(0, 0, e.z);
  MeshData m;
  m.append(make_quad(lo, ey, ez, Vec3f(-1, 0, 0)));
  m.append(make_quad(lo + ex, ey, ez, Vec3f(1, 0, 0)));
  m.append(make_quad(lo, ex, ez, Vec3f(0, -1, 0)));
  m.append(make_quad(lo + ey, ex, ez, Vec3f(0, 1, 0)));
  m.append(make_quad(lo, ex, ey, Vec3f(0, 0, -1)));
  m.append(make_quad(lo + ez, ex, ey, Vec3f(0, 0, 1)));
  return m;
}

MeshData make_icosphere(int levels) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  MeshData m;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3f& p : m.positions) p = normalize(p);
  m.triangles = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
                 {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                 {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
                 {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
  for (int level = 0; level < levels; ++level) {
    std::unordered_map<uint64_t, uint32_t> midpoint_of_edge;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      auto [it, inserted] = midpoint_of_edge.try_emplace(key, 0u);
      if (inserted) {
        it->second = static_cast<uint32_t>(m.positions.size());
        m.positions.push_back(normalize(m.positions[a] + m.positions[b]));
      }
      return it->second;
    };
    std::vector<Triangle> finer;
    finer.reserve(m.triangles.size() * 4);
    for (const Triangle& tri : m.triangles) {
      uint32_t a = midpoint(tri.v[0], tri.v[1]), b = midpoint(tri.v[1], tri.v[2]),
               c = midpoint(tri.v[2], tri.v[0]);
      finer.push_back({{tri.v[0], a, c}});
      finer.push_back({{tri.v[1], b, a}});
      finer.push_back({{tri.v[2], c, b}});
      finer.push_back({{a, b, c}});
    }
    m.triangles = std::move(finer);
  }
  m.normals = m.positions;
  return m;
}

MeshData make_torus(float major_radius, float minor_radius, int rings, int sides) {
  MeshData m;
  for (int i = 0; i < rings; ++i) {
    float phi = 2.0f * kPi * i / rings;
    Vec3f radial(std::cos(phi), 0, std::sin(phi));
    for (int j = 0; j < sides; ++j) {
      float theta = 2.0f * kPi * j / sides;
      Vec3f n = radial * std::cos(theta) + Vec3f(0, std::sin(theta), 0);
      m.positions.push_back(radial * major_radius + n * minor_radius);
      m.normals.push_back(n);
    }
  }
  auto id = [&](int i, int j) { return static_cast<uint32_t>((i % rings) * sides + (j % sides)); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      // Wound so that the cross product of the edges points along the outward normal.
      m.triangles.push_back({{id(i, j), id(i, j + 1), id(i + 1, j + 1)}});
      m.triangles.push_back({{id(i, j), id(i + 1, j + 1), id(i + 1, j)}});
    }
  return m;
}

namespace {

template <typename Rotate>
void rotate(MeshData& mesh, Vec3f pivot, Rotate r) {
  for (Vec3f& p : mesh.positions) p = r(p - pivot) + pivot;
  for (Vec3f& n : mesh.normals) n = r(n);
}

}  // namespace

void rotate_y(MeshData& mesh, float degrees, Vec3f pivot) {
  float c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
  rotate(mesh, pivot, [&](Vec3f v) { return Vec3f(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); });
}

void rotate_x(MeshData& mesh, float degrees, Vec3f pivot) {
  float c = std::cos(degrees * kPi / 180), s = std::sin(degrees * kPi / 180);
  rotate(mesh, pivot, [&](Vec3f v) { return Vec3f(v.x, c * v.y - s * v.z, s * v.y + c * v.z); });
}

void scale_translate(MeshData& mesh, float scale, Vec3f offset) {
  for (Vec3f& p : mesh.positions) p = p * scale + offset;
}

void add_mesh(Scene& scene, const std::string& name, const MeshData& mesh, uint32_t material) {
  auto base = static_cast<uint32_t>(scene.positions.size());
  auto first = static_cast<uint32_t>(scene.triangles.size());
  scene.positions.insert(scene.positions.end(), mesh.positions.begin(), mesh.positions.end());
  scene.normals.insert(scene.normals.end(), mesh.normals.begin(), mesh.normals.end());
  for (const Triangle& t : mesh.triangles) {
    scene.triangles.push_back({{t.v[0] + base, t.v[1] + base, t.v[2] + base}});
    scene.material_ids.push_back(material);
  }
  scene.meshes.push_back({name, first, static_cast<uint32_t>(mesh.triangles.size())});
}

uint32_t add_material(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

}  // namespace tuneray
