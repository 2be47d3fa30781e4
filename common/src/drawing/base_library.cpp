// ReliefKit — the model library of the base from silhouettes (thesis sect. 7.5): model files
// (vcglib's importers, binary PLY out) and a folder of models with its cache of silhouette
// features. See base_library.h.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <omp.h>
#include <sstream>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/import.h>

#include "reliefkit/drawing/base_library.h"
#include "silhouette_raster.h"

namespace fs = std::filesystem;

namespace reliefkit {

namespace {
namespace vm {
class V;
class F;
struct Used : vcg::UsedTypes<vcg::Use<V>::AsVertexType, vcg::Use<F>::AsFaceType> {};
class V : public vcg::Vertex<Used, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::Color4b,
                             vcg::vertex::TexCoord2f, vcg::vertex::BitFlags> {};
class F : public vcg::Face<Used, vcg::face::VertexRef, vcg::face::Normal3f, vcg::face::Color4b, vcg::face::BitFlags> {};
class Mesh : public vcg::tri::TriMesh<std::vector<V>, std::vector<F>> {
 public:
  ~Mesh() { ClearAttributes(); }  // vcglib's own destructor leaves the importers' attributes (OBJ materials)
};
}  // namespace vm
}  // namespace

TriMesh read_model_file(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError("The model \"" + path + "\" does not exist.");
  vm::Mesh m;
  int mask = 0;
  const int err = vcg::tri::io::Importer<vm::Mesh>::Open(m, path.c_str(), mask);
  if (err != 0 && vcg::tri::io::Importer<vm::Mesh>::ErrorCritical(err))
    throw InputError("The model \"" + path + "\" cannot be read: " + vcg::tri::io::Importer<vm::Mesh>::ErrorMsg(err) + ".");
  TriMesh out;
  std::vector<int> index(m.vert.size(), -1);
  for (size_t i = 0; i < m.vert.size(); ++i) {
    if (m.vert[i].IsD()) continue;
    const auto& p = m.vert[i].cP();
    index[i] = out.n_vertices();
    out.vertices.push_back(Vec3(p[0], p[1], p[2]));
  }
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<int, 3> t;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const long vi = vcg::tri::Index(m, f.cV(k));
      if (vi < 0 || size_t(vi) >= index.size() || index[size_t(vi)] < 0) { ok = false; break; }
      t[k] = index[size_t(vi)];
    }
    if (ok && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) out.faces.push_back(t);
  }
  if (out.faces.empty()) throw InputError("The model \"" + path + "\" has no triangles.");
  return out;
}

void write_model_ply(const std::string& path, const TriMesh& mesh) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("Cannot write \"" + path + "\".");
  out << "ply\nformat binary_little_endian 1.0\ncomment ReliefKit base model\nelement vertex " << mesh.n_vertices()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.n_faces()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : mesh.vertices) {
    const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
    out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  for (const auto& f : mesh.faces) {
    const unsigned char n = 3;
    const int32_t ids[3] = {f[0], f[1], f[2]};
    out.write(reinterpret_cast<const char*>(&n), 1);
    out.write(reinterpret_cast<const char*>(ids), sizeof ids);
  }
  if (!out) throw InputError("Cannot write \"" + path + "\" (disk full?).");
}

namespace {
bool is_model_file(const fs::path& p) {
  const std::string e = silhouette::lower(p.extension().string());
  return e == ".ply" || e == ".obj" || e == ".stl" || e == ".off";
}

// The model files under `root`, sorted.
std::vector<fs::path> model_files(const fs::path& root) {
  std::error_code ec;
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    if (it->is_regular_file(ec) && is_model_file(it->path())) files.push_back(it->path());
  std::sort(files.begin(), files.end());
  return files;
}

// One line of the cache: a model file's size, time, content hash, class and features.
struct CacheEntry {
  uintmax_t size;
  long long time;
  uint64_t hash;
  std::string kind;
  std::array<SilhouetteFeature, 3> f;
};
constexpr const char* kCacheHeader = "reliefkit-silhouettes 2";

// The cache file's entries by relative path (none when it is missing or of another version).
std::map<std::string, CacheEntry> read_feature_cache(const fs::path& path) {
  std::map<std::string, CacheEntry> cache;
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line) || line != kCacheHeader) return cache;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string rel;
    CacheEntry c;
    if (!std::getline(ls, rel, '\t')) continue;
    ls >> c.size >> c.time >> c.hash >> c.kind;
    bool ok = bool(ls);
    for (auto& f : c.f)
      for (auto& x : f) ok = ok && bool(ls >> x);
    if (ok) cache[rel] = c;
  }
  return cache;
}

bool write_feature_cache(const fs::path& path, const fs::path& root, const std::vector<fs::path>& files,
                         const std::vector<CacheEntry>& entries, const std::vector<std::string>& errors) {
  std::ofstream out(path);
  if (!out) return false;
  out << kCacheHeader << '\n';
  for (size_t i = 0; i < files.size(); ++i) {
    if (!errors[i].empty()) continue;
    out << fs::relative(files[i], root).generic_string() << '\t' << entries[i].size << ' ' << entries[i].time << ' '
        << entries[i].hash << ' ' << entries[i].kind;
    for (const auto& f : entries[i].f)
      for (float x : f) out << ' ' << x;
    out << '\n';
  }
  return bool(out);
}

long long file_time(const fs::path& p) {
  std::error_code e;
  return static_cast<long long>(fs::last_write_time(p, e).time_since_epoch().count());
}

// FNV-1a over the file's bytes.
uint64_t content_hash(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  uint64_t h = 0xcbf29ce484222325ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < in.gcount(); ++i) h = (h ^ static_cast<unsigned char>(buf[i])) * 0x100000001b3ull;
  }
  return h;
}

// How a model's features were found: computed, or from the cache entry of a file whose date
// changed but whose content did not (copied, installed, checked out: the cache is rewritten).
struct CacheUse {
  bool computed = false, redated = false;
};

// The library model of file p: its name, class (the sub-folder's name, or the name's part before
// '_'), and features from the cache when its size and date match, or its size and content (a
// copied library keeps its cache), else computed.
LibraryModel library_model(const fs::path& p, const fs::path& root, const std::map<std::string, CacheEntry>& cache,
                           CacheEntry& entry, CacheUse& use) {
  LibraryModel m;
  m.name = p.stem().string();
  m.path = p.string();
  const fs::path parent = fs::relative(p.parent_path(), root);
  m.kind = (parent.empty() || parent == ".") ? m.name.substr(0, m.name.find('_')) : parent.begin()->string();
  std::error_code e;
  entry = CacheEntry{fs::file_size(p, e), file_time(p), 0, m.kind, {}};
  const auto hit = cache.find(fs::relative(p, root).generic_string());
  const bool same_size = hit != cache.end() && hit->second.size == entry.size;
  const bool same_date = same_size && hit->second.time == entry.time;
  entry.hash = same_date ? hit->second.hash : content_hash(p);
  use.computed = !(same_date || (same_size && hit->second.hash == entry.hash));
  use.redated = !use.computed && !same_date;
  m.feature = use.computed ? model_features(normalize_to_principal_axes(read_model_file(p.string()))) : hit->second.f;
  entry.f = m.feature;
  return m;
}
}  // namespace

void add_library_folder(BaseLibrary& library, const std::string& folder, Progress progress) {
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec))
    throw InputError("The model folder \"" + folder + "\" does not exist.");
  const fs::path root(folder), cache_path = root / kFeatureCache;
  const std::vector<fs::path> files = model_files(root);
  const auto cache = read_feature_cache(cache_path);
  std::vector<LibraryModel> models(files.size());
  std::vector<std::string> errors(files.size());
  std::vector<CacheUse> uses(files.size());
  std::vector<CacheEntry> entries(files.size());
  long done = 0;
#pragma omp parallel for schedule(dynamic)
  for (long i = 0; i < long(files.size()); ++i) {
    try {
      models[size_t(i)] = library_model(files[size_t(i)], root, cache, entries[size_t(i)], uses[size_t(i)]);
    } catch (const std::exception& ex) {
      errors[size_t(i)] = ex.what();
    }
#pragma omp critical
    {
      ++done;
      if (progress && omp_get_thread_num() == 0) progress(int(100 * done / std::max<long>(1, long(files.size()))), "Reading the model library");
    }
  }
  int skipped = 0, computed = 0, redated = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    if (!errors[i].empty()) {
      if (++skipped <= 5) library.notes.push_back("Skipped: " + errors[i]);
      continue;
    }
    computed += uses[i].computed;
    redated += uses[i].redated;
    library.models.push_back(models[i]);
  }
  if (skipped > 5) library.notes.push_back("Skipped " + std::to_string(skipped - 5) + " more unreadable models.");
  if (computed == 0 && redated == 0 && cache.size() == files.size() - size_t(skipped)) return;
  const bool written = write_feature_cache(cache_path, root, files, entries, errors);
  const std::string n = std::to_string(computed);
  if (computed > 0 && written)
    library.notes.push_back("Silhouette features of " + n + " models computed and cached in " + cache_path.string() + ".");
  else if (computed > 0)
    library.notes.push_back("Silhouette features of " + n + " models computed (the folder " + folder +
                            " is not writable: they are not cached).");
  else if (redated > 0)
    library.notes.push_back("Silhouette cache of " + folder + " used: " + std::to_string(redated) +
                            " model files have new dates but the same content (a copied library)" +
                            (written ? "; the dates recorded." : "; the folder is not writable."));
}

}  // namespace reliefkit
