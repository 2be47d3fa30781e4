// The shared sparse solver (reliefkit/base/solvers.h) and the fast cotangent-matrix assembly it is fed
// with: known solutions, the fallback between the two library solvers, and failures that end in a
// report instead of a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "reliefkit/relief_edges/base_normals.h"
#include "reliefkit/base/curvature.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/multilevel.h"
#include "reliefkit/base/solvers.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

// A heat step's matrix M - t L on a jittered plane (SPD; condition number grows with t).
Eigen::SparseMatrix<double> heat_matrix(const TriMesh& m, double t) {
  LaplacianResult lap = cotangent_laplacian(m);
  Eigen::SparseMatrix<double> A = lap.M - t * lap.L;
  A.makeCompressed();
  return A;
}

// Right-hand sides of a known smooth solution (three columns).
Eigen::MatrixXd known_solution(const TriMesh& m) {
  Eigen::MatrixXd X(m.n_vertices(), 3);
  for (int v = 0; v < m.n_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    X.row(v) << std::sin(3 * p.x()) + p.y(), std::cos(2 * p.y()), p.x() * p.y() + 1;
  }
  return X;
}

double relative_error(const Eigen::MatrixXd& X, const Eigen::MatrixXd& truth) {
  return (X - truth).norm() / truth.norm();
}

// The straightforward assembly (triplets, every face, no clamping) the fast one must reproduce.
Eigen::SparseMatrix<double> triplet_laplacian(const TriMesh& m) {
  std::vector<Eigen::Triplet<double>> trip;
  for (const auto& f : m.faces) {
    double cot[3];
    bool ok = true;
    for (int j = 0; j < 3; ++j) {
      Vec3 a = m.vertices[f[(j + 1) % 3]] - m.vertices[f[j]], b = m.vertices[f[(j + 2) % 3]] - m.vertices[f[j]];
      const double s = a.cross(b).norm();
      cot[j] = a.dot(b) / s;
      ok = ok && s > 0 && std::isfinite(cot[j]);
    }
    if (!ok) continue;
    for (int j = 0; j < 3; ++j) {
      const int p = f[(j + 1) % 3], q = f[(j + 2) % 3];
      const double w = 0.5 * cot[j];
      trip.emplace_back(p, q, w), trip.emplace_back(q, p, w), trip.emplace_back(p, p, -w), trip.emplace_back(q, q, -w);
    }
  }
  Eigen::SparseMatrix<double> L(m.n_vertices(), m.n_vertices());
  L.setFromTriplets(trip.begin(), trip.end());
  return L;
}

}  // namespace

TEST(Laplacian, RowAssemblyMatchesTripletsOnJitteredMeshesAndAFan) {
  TriMesh fan;
  fan.vertices.push_back({0, 0, 0.3});
  const int n = 2000;
  for (int i = 0; i < n; ++i) fan.vertices.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
  for (int i = 0; i < n; ++i) fan.faces.push_back({0, 1 + i, 1 + (i + 1) % n});
  for (const TriMesh& m : {rktest::height_field([](double x, double y) { return 0.2 * x * y; }, 1.0, 40, 0.4, 5),
                           rktest::torus(1.0, 0.3, 60, 30, 0.3, 2), fan}) {
    LaplacianResult fast = cotangent_laplacian(m);
    const Eigen::SparseMatrix<double> ref = triplet_laplacian(m);
    const double diff = Eigen::SparseMatrix<double>(fast.L - ref).norm();
    EXPECT_LT(diff, 1e-12 * ref.norm()) << m.n_vertices() << " vertices";
    // Rows are sorted and hold their diagonal (CHOLMOD and the row-major view rely on it).
    for (int v = 0; v < m.n_vertices(); ++v) {
      const int* c = fast.L.innerIndexPtr() + fast.L.outerIndexPtr()[v];
      const int len = fast.L.outerIndexPtr()[v + 1] - fast.L.outerIndexPtr()[v];
      ASSERT_TRUE(std::is_sorted(c, c + len));
      ASSERT_TRUE(std::binary_search(c, c + len, v));
    }
  }
}

TEST(Solvers, BothSolversFindAKnownSolution) {
  TriMesh m = rktest::height_field([](double, double) { return 0.0; }, 1.0, 60, 0.3, 7);
  const double h = 2.0 / 60;
  const Eigen::SparseMatrix<double> A = heat_matrix(m, 0.5 * std::pow(10 * h, 2));
  const Eigen::MatrixXd truth = known_solution(m), B = A * truth;
  for (SolverMethod method : {SolverMethod::Iterative, SolverMethod::Direct}) {
    SolverOptions o;
    o.method = method;
    o.tolerance = 1e-10;
    Eigen::MatrixXd X;  // no guess: starts from zero
    SolveReport rep = solve_spd(A, B, X, o);
    const double err = relative_error(X, truth);
    std::printf("%s: error %.1e\n", rep.summary().c_str(), err);
    EXPECT_TRUE(rep.converged);
    EXPECT_LE(rep.residual, 1e-10);
    EXPECT_LT(err, 1e-7);
    // The report's residual is the one of the returned solution.
    const double measured = (A * X - B).colwise().norm().cwiseQuotient(B.colwise().norm()).maxCoeff();
    EXPECT_NEAR(rep.residual, measured, 1e-3 * measured + 1e-15);
    EXPECT_EQ(rep.iterations > 0, method == SolverMethod::Iterative);
  }
}

TEST(Solvers, AutoFallsBackToCholeskyWhenConjugateGradientsStop) {
  TriMesh m = rktest::height_field([](double, double) { return 0.0; }, 1.0, 60, 0.3, 7);
  const double h = 2.0 / 60;
  const Eigen::SparseMatrix<double> A = heat_matrix(m, 0.5 * std::pow(40 * h, 2));
  const Eigen::MatrixXd truth = known_solution(m), B = A * truth;
  SolverOptions o;
  o.tolerance = 1e-9;
  o.max_iterations = 5;
  // Iterative only: it stops, says so, and its residual is the true one.
  o.method = SolverMethod::Iterative;
  Eigen::MatrixXd X;
  SolveReport it = solve_spd(A, B, X, o);
  EXPECT_FALSE(it.converged);
  EXPECT_EQ(it.iterations, 5);
  EXPECT_GT(it.residual, 1e-6);
  // Auto: conjugate gradients stop, Cholesky finishes, and the report says both.
  o.method = SolverMethod::Auto;
  X.resize(0, 0);
  SolveReport rep = solve_spd(A, B, X, o);
  std::printf("%s (%s)\n", rep.summary().c_str(), rep.note.c_str());
  EXPECT_TRUE(rep.converged);
  EXPECT_NE(rep.method.find("Cholesky"), std::string::npos);
  EXPECT_NE(rep.note.find("stopped at 5 iterations"), std::string::npos);
  EXPECT_LT(relative_error(X, truth), 1e-7);
}

TEST(Solvers, MatrixThatIsNotPositiveDefiniteEndsInAReport) {
  // Indefinite: Cholesky must refuse, and Auto must not pretend to have converged.
  const int n = 200;
  Eigen::SparseMatrix<double> A(n, n);
  for (int i = 0; i < n; ++i) A.insert(i, i) = (i % 2 ? -1.0 : 1.0) * (1 + i);
  for (int i = 0; i + 1 < n; ++i) A.insert(i, i + 1) = A.insert(i + 1, i) = 0.3;
  A.makeCompressed();
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(n, 1);
  SolverOptions o;
  o.method = SolverMethod::Direct;
  Eigen::MatrixXd X;
  SolveReport d = solve_spd(A, B, X, o);
  EXPECT_FALSE(d.converged);
  EXPECT_NE(d.note.find("factorization failed"), std::string::npos) << d.note;
  o.method = SolverMethod::Auto;
  o.prefer_direct = true;
  o.max_iterations = 50;
  X.resize(0, 0);
  SolveReport a = solve_spd(A, B, X, o);
  const double measured = (A * X - B).norm() / B.norm();
  EXPECT_EQ(a.converged, measured <= o.tolerance);
  EXPECT_NEAR(a.residual, measured, 1e-6 * (1 + measured));
  EXPECT_THROW(solve_spd(A, Eigen::MatrixXd::Ones(n + 1, 1), X, o), InputError);
}

TEST(BaseNormals, WideScaleIsSolvedByTheMultilevelSolverAndAgreesWithCholesky) {
  rktest::ReliefShape s;
  s.noise = 0.1;
  rktest::Relief r = rktest::disc_on_sphere(s);
  Curvature c = compute_curvature(r.mesh);
  const double h = mesh_scale(r.mesh).edge;
  BaseNormalOptions o;
  o.scale = 4 * h;  // a narrow step, predicted below the crossover: Jacobi conjugate gradients
  BaseNormals narrow = estimate_base_normals(r.mesh, c.normal, o);
  EXPECT_LT(narrow.expected_iterations, kMultilevelAboveIterations);
  EXPECT_EQ(narrow.solve.method, "conjugate gradients");
  EXPECT_TRUE(narrow.solve.converged);
  o.scale = 100 * h;  // predicted well above the crossovers: the multilevel preconditioner
  BaseNormals wide = estimate_base_normals(r.mesh, c.normal, o);
  EXPECT_EQ(wide.solve.method, "conjugate gradients, multilevel preconditioner");
  EXPECT_GT(wide.expected_iterations, 400);
  EXPECT_LT(wide.solve.iterations, 40) << wide.solve.summary();
  o.method = SolverMethod::Direct;
  BaseNormals exact = estimate_base_normals(r.mesh, c.normal, o);
  ASSERT_TRUE(exact.solve.converged) << exact.solve.summary();
  double worst = 0;
  for (size_t v = 0; v < wide.normal.size(); ++v)
    worst = std::max(worst, std::acos(std::min(1.0, wide.normal[v].dot(exact.normal[v]))) * 180 / M_PI);
  std::printf("base normals at 100 edges: %s; %s; largest angle between them %.2e deg\n",
              wide.solve.summary().c_str(), exact.solve.summary().c_str(), worst);
  EXPECT_LT(worst, 2e-3);  // measured 4.4e-4 deg
}

// A scan in metres with unreferenced vertices (the Stanford bunny has 1,113 beside 34,834 in its
// surface): each must weigh in the right-hand side like a vertex of the surface, not like one of
// unit area, or the relative residual says nothing about the surface's normals.
TEST(BaseNormals, UnreferencedVerticesDoNotHideTheSurfacesResidual) {
  rktest::ReliefShape s;
  s.noise = 0.1;
  rktest::Relief r = rktest::disc_on_sphere(s);
  for (auto& p : r.mesh.vertices) p *= 0.01;  // a few centimetres across: vertex areas ~1e-7
  Curvature c = compute_curvature(r.mesh);
  const int surface_vertices = r.mesh.n_vertices();
  for (int k = 0; k < surface_vertices / 30; ++k) {
    r.mesh.vertices.push_back(Vec3(1, 0, 0.001 * k));
    c.normal.push_back(Vec3(0, 0, 1));
  }
  const double h = mesh_scale(r.mesh).edge;
  for (double scale_edges : {4.0, 15.0}) {  // Jacobi conjugate gradients, then the multilevel cycle
    BaseNormalOptions o;
    o.scale = scale_edges * h;
    const BaseNormals solved = estimate_base_normals(r.mesh, c.normal, o);
    o.method = SolverMethod::Direct;
    const BaseNormals exact = estimate_base_normals(r.mesh, c.normal, o);
    double worst = 0;
    for (int v = 0; v < surface_vertices; ++v)
      worst = std::max(worst, std::acos(std::min(1.0, solved.normal[size_t(v)].dot(exact.normal[size_t(v)]))) * 180 / M_PI);
    std::printf("%g edges, %d unreferenced vertices: %s; largest angle to the exact solve %.2e deg\n", scale_edges,
                surface_vertices / 30, solved.solve.summary().c_str(), worst);
    EXPECT_LT(worst, 0.2);  // measured 0.057 / 0.0054 deg; with unit weight 18.7 deg by Jacobi CG
  }
}

// The three columns of a heat step solved together by Jacobi conjugate gradients: each column to
// its tolerance, and a column whose right-hand side is zero stays at zero.
TEST(Solvers, JacobiBlockConjugateGradientsSolveEachColumn) {
  const TriMesh m = rktest::torus(3, 1, 60, 24, 0.3, 5);
  const double h = mesh_scale(m).edge;
  const Eigen::SparseMatrix<double> A = heat_matrix(m, 8 * h * h);
  Eigen::MatrixXd X_true = Eigen::MatrixXd::Random(A.rows(), 4);
  X_true.col(2).setZero();
  const Eigen::MatrixXd B = A * X_true;
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(A.rows(), 4);
  const int iterations = jacobi_cg(A, B, X, 1e-8, 1000);
  EXPECT_GT(iterations, 0);
  EXPECT_LT(iterations, 140);  // measured 69; steepest descent (no conjugation) needs 475
  for (int k = 0; k < 4; ++k) {
    const double error = (X.col(k) - X_true.col(k)).norm() / std::max(1.0, X_true.col(k).norm());
    std::printf("column %d: relative error %.2e (%d iterations)\n", k, error, iterations);
    EXPECT_LT(error, 5e-7);  // measured 0.5-1.2e-7
  }
  EXPECT_EQ(X.col(2).norm(), 0.0);
}

TEST(Multilevel, AggregatesCoverTheGraphAndEachIsConnected) {
  const TriMesh m = rktest::torus(3, 1, 60, 24, 0.3, 5);
  const LaplacianResult lap = cotangent_laplacian(m);
  int count = 0;
  const std::vector<int> aggregate = aggregate_vertices(lap.L, count);
  ASSERT_EQ(int(aggregate.size()), m.n_vertices());
  std::vector<int> size(size_t(count), 0);
  for (int a : aggregate) {
    ASSERT_GE(a, 0);
    ASSERT_LT(a, count);
    ++size[size_t(a)];
  }
  // Each aggregate is a vertex's ring and some left-over neighbours: between 1/12 and 1/5 of the
  // vertices on a torus (valence 6), and no aggregate empty.
  std::printf("%d vertices in %d aggregates\n", m.n_vertices(), count);
  EXPECT_GT(count, m.n_vertices() / 12);
  EXPECT_LT(count, m.n_vertices() / 5);
  EXPECT_GT(*std::min_element(size.begin(), size.end()), 0);
  // Connected: a walk inside each aggregate from its first vertex reaches all of it.
  const auto faces = vertex_faces(m);
  std::vector<int> reached(size_t(count), 0);
  std::vector<char> seen(aggregate.size(), 0);
  for (int start = 0; start < m.n_vertices(); ++start) {
    const int a = aggregate[size_t(start)];
    if (reached[size_t(a)] > 0) continue;
    std::vector<int> stack{start};
    seen[size_t(start)] = 1;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      ++reached[size_t(a)];
      for (Eigen::SparseMatrix<double>::InnerIterator it(lap.L, v); it; ++it)
        if (aggregate[size_t(it.row())] == a && !seen[size_t(it.row())]) seen[size_t(it.row())] = 1, stack.push_back(int(it.row()));
    }
  }
  EXPECT_EQ(reached, size);
}

namespace {

// A heat step of `edges` edge lengths on a 16,000-vertex torus, M - t L (clamped weights), with
// right-hand sides mass * (x, sin 7z, 1) (the first `columns`) and its Cholesky solution.
struct HeatStep {
  Eigen::SparseMatrix<double> A;
  Eigen::MatrixXd B, exact;
};

HeatStep heat_step_on_torus(double edges, int columns) {
  const TriMesh m = rktest::torus(3, 1, 200, 80, 0.3, 7);
  LaplacianOptions lo;
  lo.clamp_negative = true;
  LaplacianResult lap = cotangent_laplacian(m, lo);
  const double h = mesh_scale(m).edge, t = 0.5 * (edges * h) * (edges * h);
  HeatStep s;
  s.A = -t * lap.L;
  for (int v = 0; v < s.A.rows(); ++v) s.A.coeffRef(v, v) += lap.mass[v];
  s.B.resize(s.A.rows(), columns);
  for (int v = 0; v < s.A.rows(); ++v) {
    const double rhs[3] = {m.vertices[v].x(), std::sin(7 * m.vertices[v].z()), 1.0};
    for (int c = 0; c < columns; ++c) s.B(v, c) = lap.mass[v] * rhs[c];
  }
  SolverOptions o;
  o.tolerance = 1e-8;
  o.method = SolverMethod::Direct;
  EXPECT_TRUE(solve_spd(s.A, s.B, s.exact, o).converged);
  return s;
}

}  // namespace

TEST(Multilevel, SolvesAStiffHeatStepInAFewIterationsToTheCholeskyAnswer) {
  const HeatStep s = heat_step_on_torus(60, 2);
  const Eigen::SparseMatrix<double>& A = s.A;
  const Eigen::MatrixXd &B = s.B, &exact = s.exact;
  SolverOptions o;
  o.tolerance = 1e-8;
  o.max_iterations = 5000;
  o.method = SolverMethod::Iterative;
  Eigen::MatrixXd jacobi;
  const SolveReport plain = solve_spd(A, B, jacobi, o);
  o.method = SolverMethod::Multilevel;
  Eigen::MatrixXd X;
  const SolveReport two = solve_spd(A, B, X, o);
  std::printf("heat step of 60 edges, %ld unknowns: %s; %s; |X - exact| / |exact| = %.1e\n", long(A.rows()),
              two.summary().c_str(), plain.summary().c_str(), (X - exact).norm() / exact.norm());
  ASSERT_TRUE(two.converged) << two.summary();
  EXPECT_EQ(two.method, "conjugate gradients, multilevel preconditioner");
  EXPECT_LT(two.iterations * 8, plain.iterations);
  EXPECT_LT((X - exact).norm() / exact.norm(), 1e-6);
}

// The V-cycle through more levels (forced on a small mesh by a low factorization limit): still a
// valid preconditioner (symmetric, so conjugate gradients converge to the Cholesky answer) and
// still a fraction of Jacobi's iterations.
TEST(Multilevel, DeeperCyclesSolveTheHeatStepToTheCholeskyAnswer) {
  const HeatStep s = heat_step_on_torus(15, 3);
  // Measured 26, 36 and 44 iterations for 2, 3 and 4 levels.
  const std::vector<std::pair<int, int>> limit_and_iterations = {{kLargestFactorizedLevel, 32}, {1500, 45}, {100, 55}};
  for (auto [largest, most_iterations] : limit_and_iterations) {
    const MultilevelPreconditioner cycle(s.A, largest);
    ASSERT_TRUE(cycle.ok());
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(s.B.rows(), s.B.cols());
    const int iterations = preconditioned_cg(cycle, s.B, X, 1e-8, 500);
    const double error = (X - s.exact).norm() / s.exact.norm();
    std::printf("%d levels, %d unknowns factorized: %d iterations, |X - exact| / |exact| = %.1e\n", cycle.levels(),
                cycle.coarse_size(), iterations, error);
    EXPECT_LE(cycle.coarse_size(), std::max(largest, 200));
    EXPECT_LT(error, 5e-7);  // measured 0.5-1.2e-7
    EXPECT_LE(iterations, most_iterations);
  }
}

// A Hermitian positive-definite system with genuinely complex couplings: D^H (M - tL) D for
// random unit phases D (a connection Laplacian of rotations that compose to identity around
// loops), on the heat step's torus.
TEST(Hermitian, ComplexConjugateGradientsAgreeWithCholeskyOnTheRealForm) {
  const HeatStep s = heat_step_on_torus(4, 1);
  const int n = int(s.A.rows());
  std::vector<std::complex<double>> phase(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) phase[size_t(i)] = std::polar(1.0, 2.4 * i + 0.3 * std::sin(i));
  std::vector<Eigen::Triplet<std::complex<double>>> entries;
  for (int c = 0; c < n; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(s.A, c); it; ++it)
      entries.emplace_back(int(it.row()), c, std::conj(phase[size_t(it.row())]) * it.value() * phase[size_t(c)]);
  HermitianMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXcd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::conj(phase[size_t(i)]) * std::complex<double>(s.B(i, 0), 0.5 * s.B(i, 0));
  // The exact answer: phase times the real system's solution for the real and imaginary parts.
  Eigen::VectorXcd exact(n);
  for (int i = 0; i < n; ++i) exact[i] = std::conj(phase[size_t(i)]) * std::complex<double>(s.exact(i, 0), 0.5 * s.exact(i, 0));
  SolverOptions o;
  o.tolerance = 1e-8;
  Eigen::VectorXcd x;
  const SolveReport cg = solve_hpd(A, b, x, o);
  std::printf("Hermitian %d unknowns: %s, |x - exact| / |exact| = %.1e\n", n, cg.summary().c_str(),
              (x - exact).norm() / exact.norm());
  EXPECT_EQ(cg.method, "conjugate gradients");
  EXPECT_TRUE(cg.converged);
  EXPECT_LT((x - exact).norm() / exact.norm(), 1e-6);
  // Stopped after two iterations, the solve falls back to CHOLMOD on the real form.
  o.max_iterations = 2;
  Eigen::VectorXcd y;
  const SolveReport fallback = solve_hpd(A, b, y, o);
  EXPECT_EQ(fallback.method, "Cholesky (CHOLMOD)") << fallback.summary();
  EXPECT_NE(fallback.note.find("complex conjugate gradients stopped at 2 iterations"), std::string::npos);
  EXPECT_LT((y - exact).norm() / exact.norm(), 1e-8);
}

TEST(Hermitian, RealFormWritesEachEntryAsARotationBlock) {
  HermitianMatrix A(2, 2);
  std::vector<Eigen::Triplet<std::complex<double>>> e = {{0, 0, {3, 0}}, {0, 1, {1, 2}}, {1, 0, {1, -2}}, {1, 1, {5, 0}}};
  A.setFromTriplets(e.begin(), e.end());
  const Eigen::MatrixXd R = Eigen::MatrixXd(real_form(A));
  Eigen::MatrixXd expected(4, 4);
  expected << 3, 0, 1, -2,
              0, 3, 2, 1,
              1, 2, 5, 0,
              -2, 1, 0, 5;
  EXPECT_EQ(R, expected);
  EXPECT_EQ(R, R.transpose());
}
