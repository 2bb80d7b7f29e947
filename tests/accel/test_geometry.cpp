#include "test_geometry.h"

#include <map>
#include <tuple>
#include <utility>

namespace tuneray::test {

Mesh make_icosphere(int levels, Vec3f center) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3f> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3f& p : v) p = normalize(p);
  std::vector<Triangle> f = {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}},
                             {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},
                             {{3, 9, 4}},  {{3, 4, 2}},  {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},
                             {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}},  {{8, 6, 7}},  {{9, 8, 1}}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalize((v[a] + v[b]) * 0.5f));
      uint32_t id = static_cast<uint32_t>(v.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<Triangle> next;
    for (const Triangle& tri : f) {
      uint32_t a = tri.v[0], b = tri.v[1], c = tri.v[2];
      uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {{{a, ab, ca}}, {{b, bc, ab}}, {{c, ca, bc}}, {{ab, bc, ca}}});
    }
    f = std::move(next);
  }
  Mesh m;
  for (Vec3f& p : v) p = p + center;
  m.positions = std::move(v);
  m.triangles = std::move(f);
  return m;
}

Mesh make_grid_box(int n) {
  Mesh m;
  std::map<std::tuple<int, int, int>, uint32_t> ids;
  auto vertex = [&](int x, int y, int z) {
    auto key = std::make_tuple(x, y, z);
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    m.positions.push_back(Vec3f(float(x), float(y), float(z)) / float(n) - Vec3f(0.5f));
    uint32_t id = static_cast<uint32_t>(m.positions.size() - 1);
    ids.emplace(key, id);
    return id;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side <= n; side += n) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto at = [&](int a, int b) {
            int c[3];
            c[axis] = side;
            c[(axis + 1) % 3] = a;
            c[(axis + 2) % 3] = b;
            return vertex(c[0], c[1], c[2]);
          };
          uint32_t p00 = at(i, j), p10 = at(i + 1, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1);
          m.triangles.push_back({{p00, p10, p11}});
          m.triangles.push_back({{p00, p11, p01}});
        }
      }
    }
  }
  return m;
}

}  // namespace tuneray::test
