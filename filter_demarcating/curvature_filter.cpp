#include "curvature_filter.h"

#include <chrono>
#include <cmath>

#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/base/curvature.h"

namespace reliefkit::ml {
namespace {

enum class Quantity { Mean, Gaussian, Maximal, Minimal, Curvedness, Keep };
const QStringList kQuantities = {"Mean curvature", "Gaussian curvature", "Maximal curvature (k1)",
                                 "Minimal curvature (k2)", "Curvedness", "None (keep vertex quality)"};
const QStringList kEstimators = {"Cubic jet fit (accurate)", "Per-face fit (faster, Rusinkiewicz 2004)"};

const char* kInfo =
    "Estimates, at every vertex, the <b>principal curvatures and directions</b> and the "
    "<b>curvature-derivative tensor</b> C = (a, b, c, d): how fast the curvature changes across the "
    "surface. It is the ground of demarcating curves, relief edges and ridges &amp; valleys.<br><br>"
    "<b>Outputs</b> (on this layer):<ul>"
    "<li>principal directions and curvatures (MeshLab's <i>Show Curvature</i> decoration draws them);</li>"
    "<li>per-vertex attributes <code>k1</code>, <code>k2</code> (k1 &ge; k2) and <code>dcurv_a</code>, "
    "<code>dcurv_b</code>, <code>dcurv_c</code>, <code>dcurv_d</code> (the tensor in the principal frame);</li>"
    "<li>vertex quality = the quantity you choose, ready for <i>Colorize by vertex quality</i>.</li></ul>"
    "Sign: curvature is positive on convex parts (a ball, the top of a raised letter) and negative on "
    "concave ones (a groove, an engraved line), for outward-facing normals. Units: 1/length.<br><br>"
    "Method: a least-squares cubic height function (osculating jet) is fitted over the two-ring of "
    "every vertex (F. Cazals, M. Pouget, <b>\"Estimating differential quantities using polynomial "
    "fitting of osculating jets\"</b>, SGP 2003), or, faster but less accurate on irregular meshes, "
    "per-face fits (S. Rusinkiewicz, <b>\"Estimating curvatures and their derivatives on triangle "
    "meshes\"</b>, 3DPVT 2004). The tensor is that of eq. 3.1 in M. Kolomenkin's thesis on curves on "
    "surfaces (demarcating curves, A. Tal, M. Kolomenkin, I. Shimshoni, SIGGRAPH Asia 2008).";

double quantity(Quantity q, double k1, double k2) {
  switch (q) {
    case Quantity::Mean: return 0.5 * (k1 + k2);
    case Quantity::Gaussian: return k1 * k2;
    case Quantity::Maximal: return k1;
    case Quantity::Minimal: return k2;
    case Quantity::Curvedness: return std::sqrt(0.5 * (k1 * k1 + k2 * k2));
    case Quantity::Keep: return 0;
  }
  return 0;
}

void parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichEnum("estimator", 0, kEstimators, "Estimator",
                        "How curvature is measured. The jet fit is accurate also on irregular scans. The "
                        "per-face fit is a little faster and fine for curvature on regular meshes, but its "
                        "derivatives (dcurv_*) are unreliable on irregular triangulations."));
  add_presmoothing(par);
  par.addParam(RichEnum("quality", 0, kQuantities, "Vertex quality",
                        "What to store in vertex quality, for Filters > Color Creation and Processing > "
                        "Colorize by vertex quality. Curvedness = sqrt((k1^2 + k2^2) / 2)."));
}

void apply(FilterCall& call) {
  auto t0 = std::chrono::steady_clock::now();
  const int estimator = read_enum(call, "estimator", "Estimator", kEstimators.size());
  const Length presmoothing = read_presmoothing(call);
  const auto q = static_cast<Quantity>(read_enum(call, "quality", "Vertex quality", kQuantities.size()));
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  CurvatureOptions opt;
  opt.estimator = estimator == 1 ? CurvatureEstimator::FaceFit : CurvatureEstimator::Jet;
  auto t1 = std::chrono::steady_clock::now();
  ScaledCurvature sc = curvature_at_scale(surface, presmoothing, opt.estimator, call.progress);
  opt.smoothing_scale = sc.presmoothing;
  const Curvature& c = *sc.curvature;
  auto t2 = std::chrono::steady_clock::now();

  CMeshO& cm = call.mesh().cm;
  call.mesh().updateDataMask(MeshModel::MM_VERTCURVDIR | MeshModel::MM_VERTQUALITY);
  const int nv = view.mesh.n_vertices();
  using Alloc = vcg::tri::Allocator<CMeshO>;
  auto h_k1 = Alloc::GetPerVertexAttribute<Scalarm>(cm, "k1");
  auto h_k2 = Alloc::GetPerVertexAttribute<Scalarm>(cm, "k2");
  auto h_a = Alloc::GetPerVertexAttribute<Scalarm>(cm, "dcurv_a");
  auto h_b = Alloc::GetPerVertexAttribute<Scalarm>(cm, "dcurv_b");
  auto h_c = Alloc::GetPerVertexAttribute<Scalarm>(cm, "dcurv_c");
  auto h_d = Alloc::GetPerVertexAttribute<Scalarm>(cm, "dcurv_d");
  auto write = [&](int i, CVertexO* v) {
    v->PD1() = Point3m(Scalarm(c.dir1[i].x()), Scalarm(c.dir1[i].y()), Scalarm(c.dir1[i].z()));
    v->PD2() = Point3m(Scalarm(c.dir2[i].x()), Scalarm(c.dir2[i].y()), Scalarm(c.dir2[i].z()));
    v->K1() = Scalarm(c.k1[i]);
    v->K2() = Scalarm(c.k2[i]);
    if (q != Quantity::Keep) v->Q() = float(quantity(q, c.k1[i], c.k2[i]));
    h_k1[v] = Scalarm(c.k1[i]);
    h_k2[v] = Scalarm(c.k2[i]);
    h_a[v] = Scalarm(c.dcurv[i].a);
    h_b[v] = Scalarm(c.dcurv[i].b);
    h_c[v] = Scalarm(c.dcurv[i].c);
    h_d[v] = Scalarm(c.dcurv[i].d);
  };
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nv; ++i) write(i, view.vertex_of[i]);
  for (const auto& [i, v] : view.also) write(i, v);  // welded duplicates

  auto t3 = std::chrono::steady_clock::now();
  auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  call.log(QString("Curvature and derivatives of %1 vertices / %2 faces in %3 s (copy %6 s, estimate %7 s, "
                   "write-back %8 s; %4, pre-smoothing %5 mesh units).")
               .arg(thousands(nv))
               .arg(thousands(view.mesh.n_faces()))
               .arg(sec(t0, t3), 0, 'f', 3)
               .arg(opt.estimator == CurvatureEstimator::Jet ? "jet fit" : "per-face fit")
               .arg(opt.smoothing_scale, 0, 'g', 4)
               .arg(sec(t0, t1), 0, 'f', 3)
               .arg(sec(t1, t2), 0, 'f', 3)
               .arg(sec(t2, t3), 0, 'f', 3));
  call.log(scale_summary(sc.scale, sc.noise, sc.presmoothing, presmoothing));
  if (!c.bad_vertices.empty() || c.degenerate_faces > 0)
    call.log(QString("%1 vertices had no usable neighbourhood (isolated or only degenerate faces): curvature 0 "
                     "there; %2 degenerate faces were skipped.")
                 .arg(thousands(static_cast<long long>(c.bad_vertices.size())))
                 .arg(thousands(c.degenerate_faces)));
  if (q != Quantity::Keep) {
    std::vector<float> qs;
    qs.reserve(nv);
    for (int i = 0; i < nv; ++i) qs.push_back(view.vertex_of[i]->Q());
    auto pct = [&](int k) {
      std::nth_element(qs.begin(), qs.begin() + k, qs.end());
      return qs[k];
    };
    call.log(QString("Vertex quality = %1: 5th percentile %2, median %3, 95th percentile %4.")
                 .arg(kQuantities[int(q)])
                 .arg(pct(nv / 20), 0, 'g', 4)
                 .arg(pct(nv / 2), 0, 'g', 4)
                 .arg(pct((nv * 19) / 20), 0, 'g', 4));
  }
}

}  // namespace

FilterSpec curvature_tensor_filter(int id) {
  return FilterSpec{id,
                    "Compute Curvature Tensor and Derivatives",
                    kInfo,
                    // Not a colouring filter: MeshLab would switch the view to the (white) vertex colours.
                    ml::FilterInterface::Normal,
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTCURVDIR | MeshModel::MM_VERTQUALITY,
                    parameters,
                    apply};
}

}  // namespace reliefkit::ml
