// rk_make_bases — writes ReliefKit's library of base models (reliefkit/drawing/base_library.h) into a
// folder: <folder>/<class>/<class>_NN.ply for every class, and the silhouette-feature cache, so
// that "Base from Drawing Silhouette" finds them ready. Run by the build (build/bases, copied
// into the private prefix as share/reliefkit/bases).
// Usage: rk_make_bases FOLDER [MODELS_PER_CLASS (36)] [VERTICES_AROUND (96)]
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "reliefkit/drawing/base_library.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FOLDER [MODELS_PER_CLASS] [VERTICES_AROUND]\n", argv[0]);
    return 2;
  }
  namespace fs = std::filesystem;
  const fs::path root(argv[1]);
  const int per_class = argc > 2 ? std::atoi(argv[2]) : 36;
  const int around = argc > 3 ? std::atoi(argv[3]) : 96;
  try {
    const auto specs = reliefkit::standard_base_specs(per_class);
    long faces = 0;
    for (const auto& s : specs) {
      const fs::path dir = root / reliefkit::base_class_name(s.kind);
      fs::create_directories(dir);
      const auto mesh = reliefkit::make_base_model(s, around);
      faces += mesh.n_faces();
      reliefkit::write_model_ply((dir / (s.name + ".ply")).string(), mesh);
    }
    reliefkit::BaseLibrary lib;
    reliefkit::add_library_folder(lib, root.string());
    std::printf("rk_make_bases: %zu models (%d classes, %ld faces) in %s\n", lib.models.size(), reliefkit::kBaseClasses,
                faces, root.string().c_str());
    for (const auto& n : lib.notes) std::printf("  %s\n", n.c_str());
    return lib.models.size() == specs.size() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rk_make_bases: %s\n", e.what());
    return 1;
  }
}
