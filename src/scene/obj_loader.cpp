// Wavefront OBJ + MTL through tinyobjloader: we keep its parser and add validation, fan
// triangulation, vertex welding per (position, normal, uv) triple and smooth normals.
#include <tiny_obj_loader.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "scene/loaders.h"
#include "scene/mtl_material.h"
#include "scene/normals.h"
#include "scene/texture_cache.h"

namespace tuneray {

namespace {

namespace fs = std::filesystem;
constexpr uint32_t kNone = ~0u;

// Resolves mtllib names next to the OBJ and remembers what it could not find, so that the
// loader can fail with a clear message instead of tinyobjloader's silent default material.
class MtlFileReader : public tinyobj::MaterialReader {
 public:
  explicit MtlFileReader(fs::path dir) : dir_(std::move(dir)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn,
                  std::string* err) override {
    fs::path path = dir_ / fs::path(name).make_preferred();
    std::ifstream in(path);
    if (!in) {
      if (missing_.empty()) missing_ = path.string();
      return false;
    }
    tinyobj::LoadMtl(material_map, materials, &in, warn, err);
    loaded_.push_back({path.string(), materials->size()});
    return true;
  }

  const std::string& missing() const { return missing_; }
  // The MTL file that defined material `index`.
  std::string file_of(size_t index) const {
    for (const auto& [file, end] : loaded_)
      if (index < end) return file;
    return "";
  }

 private:
  fs::path dir_;
  std::string missing_;
  std::vector<std::pair<std::string, size_t>> loaded_;  // file, material count after it
};

Color to_color(const float c[3]) {
  return {c[0], c[1], c[2]};
}

std::string texture_path(const fs::path& dir, std::string name) {
  for (char& c : name)
    if (c == '\\') c = '/';
  fs::path p(name);
  return (p.is_absolute() ? p : dir / p).string();
}

Material convert_material(const tinyobj::material_t& m, const fs::path& dir,
                          const std::string& mtl_file, TextureCache& textures) {
  MtlParams p;
  p.name = m.name;
  p.kd = to_color(m.diffuse);
  p.ks = to_color(m.specular);
  p.ke = to_color(m.emission);
  p.tf = to_color(m.transmittance);
  p.ns = m.shininess;
  p.ni = m.ior;
  p.dissolve = m.dissolve;
  p.illum = m.illum;
  p.aniso = m.anisotropy;
  Material out = material_from_mtl(p);
  if (!m.diffuse_texname.empty())
    out.base_texture = textures.get(texture_path(dir, m.diffuse_texname), mtl_file);
  return out;
}

struct IndexKey {
  int v, n, t;
  bool operator==(const IndexKey&) const = default;
};
struct IndexKeyHash {
  size_t operator()(const IndexKey& k) const {
    uint64_t h = static_cast<uint32_t>(k.v) * 0x9e3779b97f4a7c15ULL;
    h ^= (static_cast<uint64_t>(static_cast<uint32_t>(k.n)) << 32 | static_cast<uint32_t>(k.t)) +
         0x7f4a7c159e3779b9ULL + (h << 6) + (h >> 2);
    return h;
  }
};

// Turns OBJ's separate position/normal/uv indices into one index per unique triple.
class VertexWelder {
 public:
  VertexWelder(const tinyobj::attrib_t& attrib, Scene& scene)
      : attrib_(attrib), scene_(scene), first_of_position_(attrib.vertices.size() / 3, kNone) {}

  uint32_t vertex(const tinyobj::index_t& idx) {
    uint32_t& first = first_of_position_[idx.vertex_index];
    if (first == kNone) return first = create(idx);
    if (normal_index_[first] == idx.normal_index && uv_index_[first] == idx.texcoord_index)
      return first;
    auto [it, inserted] =
        others_.try_emplace({idx.vertex_index, idx.normal_index, idx.texcoord_index}, 0u);
    if (inserted) it->second = create(idx);
    return it->second;
  }

  // Area-weighted smooth normals, summed per OBJ position so that vertices split only by their
  // UVs still share one normal, for every vertex whose file gave it none (or a zero one).
  void fill_missing_normals() {
    std::vector<Vec3f> sums(first_of_position_.size(), Vec3f(0.0f));
    bool any_missing = false;
    for (size_t i = 0; i < scene_.normals.size(); ++i) any_missing |= normal_index_[i] < 0;
    if (!any_missing) return;
    for (const Triangle& t : scene_.triangles) {
      const Vec3f n =
          area_normal(scene_.positions[t.v[0]], scene_.positions[t.v[1]], scene_.positions[t.v[2]]);
      for (uint32_t v : t.v) sums[position_index_[v]] += n;
    }
    for (size_t i = 0; i < scene_.normals.size(); ++i)
      if (normal_index_[i] < 0) scene_.normals[i] = normalize_or_up(sums[position_index_[i]]);
  }

 private:
  uint32_t create(const tinyobj::index_t& idx) {
    auto id = static_cast<uint32_t>(scene_.positions.size());
    const float* p = &attrib_.vertices[3 * static_cast<size_t>(idx.vertex_index)];
    scene_.positions.emplace_back(p[0], p[1], p[2]);
    int normal = idx.normal_index;
    Vec3f n(0.0f);
    if (normal >= 0) {
      const float* f = &attrib_.normals[3 * static_cast<size_t>(normal)];
      n = Vec3f(f[0], f[1], f[2]);
      float len = length(n);
      if (len > 0.0f && std::isfinite(len))
        n = n / len;
      else
        normal = -1;  // unusable: regenerate
    }
    scene_.normals.push_back(n);
    Vec2f uv;
    if (idx.texcoord_index >= 0) {
      const float* t = &attrib_.texcoords[2 * static_cast<size_t>(idx.texcoord_index)];
      uv = Vec2f(t[0], t[1]);
    }
    scene_.uvs.push_back(uv);
    position_index_.push_back(idx.vertex_index);
    normal_index_.push_back(normal);
    uv_index_.push_back(idx.texcoord_index);
    return id;
  }

  const tinyobj::attrib_t& attrib_;
  Scene& scene_;
  std::vector<uint32_t> first_of_position_;
  std::unordered_map<IndexKey, uint32_t, IndexKeyHash> others_;
  std::vector<int> position_index_, normal_index_, uv_index_;
};

void check_finite_positions(const std::string& file, const std::vector<float>& v) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw SceneError(file + ": vertex " + std::to_string(i / 3 + 1) +
                       " has a non-finite coordinate");
}

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "abc") as 0 without a word, so
// vertex lines are checked before it sees them: every coordinate must look like a number.
void check_vertex_lines(const std::string& file, std::string_view text) {
  size_t line_number = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    size_t start = line.find_first_not_of(" \t");
    if (start == std::string_view::npos || line[start] != 'v') continue;
    line.remove_prefix(start);
    if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t' && line[1] != 'n' && line[1] != 't'))
      continue;
    size_t i = line[1] == 'n' || line[1] == 't' ? 2 : 1;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i >= line.size() || line[i] == '#') break;
      char c = line[i];
      if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.'))
        throw SceneError(file + ": line " + std::to_string(line_number) + ": vertex coordinate '" +
                         std::string(line.substr(i, line.find_first_of(" \t\r", i) - i)) +
                         "' is not a finite number");
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    }
  }
}

void check_index(const std::string& file, const std::string& shape, size_t face, const char* what,
                 int index, size_t count, bool optional) {
  if ((optional && index == -1) || (index >= 0 && static_cast<size_t>(index) < count)) return;
  throw SceneError(file + ": face " + std::to_string(face + 1) + " of '" + shape + "' has " + what +
                   " index " + std::to_string(index + 1) + " out of range (the file has " +
                   std::to_string(count) + ")");
}

}  // namespace

Scene load_obj(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw SceneError(path + ": cannot open file");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  check_vertex_lines(path, text);
  std::istringstream in(std::move(text));
  const fs::path dir = fs::path(path).parent_path();

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mtl;
  std::string warn, err;
  MtlFileReader mtl_reader(dir);
  // Triangulation off: tinyobjloader's ear clipper can drop faces; we fan-triangulate ourselves.
  bool ok = tinyobj::LoadObj(&attrib, &shapes, &mtl, &warn, &err, &in, &mtl_reader,
                             /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok || !err.empty()) throw SceneError(path + ": malformed OBJ: " + err);
  if (!mtl_reader.missing().empty())
    throw SceneError(path + ": material library '" + mtl_reader.missing() + "' not found");
  if (warn.find("Degenerated face") != std::string::npos)
    throw SceneError(path + ": malformed OBJ: a face has fewer than 3 vertices");
  check_finite_positions(path, attrib.vertices);

  Scene scene;
  scene.source = path;
  scene.name = fs::path(path).stem().string();
  TextureCache textures(scene.textures);
  for (size_t i = 0; i < mtl.size(); ++i)
    scene.materials.push_back(convert_material(mtl[i], dir, mtl_reader.file_of(i), textures));
  uint32_t default_material = kNone;

  const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3,
               nt = attrib.texcoords.size() / 2;
  VertexWelder welder(attrib, scene);
  size_t face_number = 0;
  bool any_uv = false;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t corners = 0;
    for (unsigned char n : mesh.num_face_vertices) corners += n;
    if (corners != mesh.indices.size())
      throw SceneError(path + ": '" + shape.name + "' has a polygon with more than 255 vertices");
    auto first_triangle = static_cast<uint32_t>(scene.triangles.size());
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f, ++face_number) {
      const size_t n = mesh.num_face_vertices[f];
      uint32_t ids[256];
      for (size_t k = 0; k < n; ++k) {
        const tinyobj::index_t& idx = mesh.indices[offset + k];
        check_index(path, shape.name, face_number, "vertex", idx.vertex_index, nv, false);
        check_index(path, shape.name, face_number, "normal", idx.normal_index, nn, true);
        check_index(path, shape.name, face_number, "texture coordinate", idx.texcoord_index, nt,
                    true);
        any_uv |= idx.texcoord_index >= 0;
        ids[k] = welder.vertex(idx);
      }
      offset += n;
      int mat = mesh.material_ids[f];
      uint32_t material = static_cast<uint32_t>(mat);
      if (mat < 0 || static_cast<size_t>(mat) >= scene.materials.size()) {
        if (default_material == kNone) {
          default_material = static_cast<uint32_t>(scene.materials.size());
          scene.materials.push_back(Material{.name = "default"});
        }
        material = default_material;
      }
      for (size_t k = 2; k < n; ++k) {
        scene.triangles.push_back({{ids[0], ids[k - 1], ids[k]}});
        scene.material_ids.push_back(material);
      }
    }
    auto count = static_cast<uint32_t>(scene.triangles.size()) - first_triangle;
    if (count == 0) continue;
    if (!scene.meshes.empty() && scene.meshes.back().name == shape.name)
      scene.meshes.back().count += count;
    else
      scene.meshes.push_back({shape.name, first_triangle, count});
  }
  if (scene.triangles.empty()) throw SceneError(path + ": no triangles");
  welder.fill_missing_normals();
  if (!any_uv) scene.uvs.clear();
  if (default_material != kNone)
    scene.notes.push_back("faces without a known material use a default grey Lambert");
  return scene;
}

}  // namespace tuneray
