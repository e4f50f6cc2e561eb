// The 3D frame element (core/include/femup/core/fe/frame3d.h) and the jacket-like space
// frame builder (core/include/femup/core/fe/space_frame.h), checked against closed-form
// beam theory (cantilever tip deflections P L^3 / 3 E I, P L / E A, T L / G J,
// the Timoshenko shear term P L / G As, Euler-Bernoulli and torsional
// cantilever frequencies), rigid-body properties (six zero-energy modes, mass
// m for a translation, m L^2 / 12 for a rotation), invariance under rotation,
// member masses summed by hand from the spec, counts from the spec's
// definition, and the dense eigensolver for the sparse one.
#include "femup/core/fe/space_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/fe/frame3d.h"
#include "femup/core/linalg/modal.h"
#include "structure_specs.h"

namespace femup {
namespace {

using Eigen::Vector3d;

// A section with all properties different, so that a mix-up shows.
FrameSection3d TestSection() {
  FrameSection3d s;
  s.E = 210e9;
  s.G = 80e9;
  s.A = 0.01;
  s.Iy = 2e-5;
  s.Iz = 8e-5;
  s.J = 3e-5;
  s.rho = 7850;
  s.Ip = 1e-4;
  s.shear_area_y = 0.01 * 5.0 / 6.0;
  s.shear_area_z = 0.01 * 0.6;
  return s;
}

struct Axes {
  Vector3d x, y, z;  // member axis and local y, z as the header defines them
};

Axes LocalAxes(const Vector3d& dir, const Vector3d& ref) {
  Axes a;
  a.x = dir.normalized();
  a.y = (ref - ref.dot(a.x) * a.x).normalized();
  a.z = a.x.cross(a.y);
  return a;
}

// A straight cantilever of `n` elements from the origin along `dir` (length
// `length`), the origin clamped; dense K and M over the 6 n free DOFs (node k
// at DOFs 6 (k - 1) .. 6 k - 1, the tip last).
struct Line {
  Eigen::MatrixXd k, m;
};

Line Cantilever(const FrameSection3d& s, const Vector3d& dir, double length, int n,
                const Vector3d& ref, BeamTheory theory = BeamTheory::kEulerBernoulli) {
  Line line;
  line.k = line.m = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  const Vector3d step = dir.normalized() * length / n;
  for (int e = 0; e < n; ++e) {
    const Matrix12 ke = Frame3dStiffness(s, e * step, (e + 1) * step, ref, theory);
    const Matrix12 me = Frame3dConsistentMass(s, e * step, (e + 1) * step, ref, theory);
    for (int i = 0; i < 12; ++i) {
      const int gi = 6 * (e - 1) + i;  // node e is at 6 (e - 1)
      if (gi < 0) continue;
      for (int j = 0; j < 12; ++j) {
        const int gj = 6 * (e - 1) + j;
        if (gj < 0) continue;
        line.k(gi, gj) += ke(i, j);
        line.m(gi, gj) += me(i, j);
      }
    }
  }
  return line;
}

// Tip translation and rotation under a tip force f and moment c.
void TipResponse(const Line& line, const Vector3d& f, const Vector3d& c, Vector3d* u,
                 Vector3d* r) {
  const int n = static_cast<int>(line.k.rows());
  Eigen::VectorXd load = Eigen::VectorXd::Zero(n);
  load.segment<3>(n - 6) = f;
  load.segment<3>(n - 3) = c;
  const Eigen::VectorXd x = line.k.ldlt().solve(load);
  *u = x.segment<3>(n - 6);
  *r = x.segment<3>(n - 3);
}

struct AxisCase {
  const char* name;
  Vector3d dir, ref;
};

std::vector<AxisCase> AxisCases() {
  return {{"X", Vector3d(1, 0, 0), Vector3d(0, 1, 0)},
          {"Y", Vector3d(0, 1, 0), Vector3d(0, 0, 1)},
          {"Z", Vector3d(0, 0, 1), Vector3d(1, 0, 0)},
          {"skew", Vector3d(1, 2, 3).normalized(), Vector3d(0.3, -1, 0.2)}};
}

TEST(SpaceFrameElement, CantileverStaticTipResponseAlongEachAxis) {
  const FrameSection3d s = TestSection();
  const double l = 4.0, p = 1000.0, t = 500.0;
  for (const AxisCase& c : AxisCases()) {
    for (int n : {1, 5}) {
      SCOPED_TRACE(std::string(c.name) + " with " + std::to_string(n) + " elements");
      const Axes a = LocalAxes(c.dir, c.ref);
      const Line line = Cantilever(s, c.dir, l, n, c.ref);
      Vector3d u, r;
      auto near = [](double got, double want) {
        EXPECT_NEAR(got, want, 1e-9 * std::abs(want));
      };
      // Force along local y: bending in the x-y plane, E Iz.
      TipResponse(line, p * a.y, Vector3d::Zero(), &u, &r);
      near(u.dot(a.y), p * l * l * l / (3 * s.E * s.Iz));
      near(r.dot(a.z), p * l * l / (2 * s.E * s.Iz));
      EXPECT_NEAR(u.dot(a.z), 0.0, 1e-9 * u.norm());
      EXPECT_NEAR(u.dot(a.x), 0.0, 1e-9 * u.norm());
      // Force along local z: bending in the x-z plane, E Iy.
      TipResponse(line, p * a.z, Vector3d::Zero(), &u, &r);
      near(u.dot(a.z), p * l * l * l / (3 * s.E * s.Iy));
      near(r.dot(a.y), -p * l * l / (2 * s.E * s.Iy));
      EXPECT_NEAR(u.dot(a.y), 0.0, 1e-9 * u.norm());
      // Axial force and torque.
      TipResponse(line, p * a.x, Vector3d::Zero(), &u, &r);
      near(u.dot(a.x), p * l / (s.E * s.A));
      TipResponse(line, Vector3d::Zero(), t * a.x, &u, &r);
      near(r.dot(a.x), t * l / (s.G * s.J));
      EXPECT_NEAR(u.norm(), 0.0, 1e-9 * l * r.norm());
    }
  }
}

TEST(SpaceFrameElement, CantileverFrequenciesAlongEachAxis) {
  const FrameSection3d s = TestSection();
  const double l = 4.0, beta = 1.875104068711961;
  const double f_y = beta * beta *
                     std::sqrt(s.E * s.Iz / (s.rho * s.A * std::pow(l, 4))) /
                     (2 * M_PI);  // x-y plane
  const double f_z = beta * beta *
                     std::sqrt(s.E * s.Iy / (s.rho * s.A * std::pow(l, 4))) /
                     (2 * M_PI);  // x-z plane, lower (Iy < Iz)
  const double f_t = M_PI / 2 * std::sqrt(s.G * s.J / (s.rho * s.Ip)) / l / (2 * M_PI);
  const int n = 20;
  for (const AxisCase& c : AxisCases()) {
    SCOPED_TRACE(c.name);
    const Axes a = LocalAxes(c.dir, c.ref);
    const Line line = Cantilever(s, c.dir, l, n, c.ref);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(line.k, line.m);
    ASSERT_EQ(es.info(), Eigen::Success);
    const Eigen::VectorXd f = es.eigenvalues().cwiseSqrt() / (2 * M_PI);
    EXPECT_NEAR(f[0], f_z, 1e-6 * f_z);
    EXPECT_NEAR(f[1], f_y, 1e-6 * f_y);
    // Mode 1 moves the tip along local z, mode 2 along local y.
    const Eigen::MatrixXd& v = es.eigenvectors();
    const int tip = 6 * (n - 1);
    EXPECT_GT(std::abs(v.col(0).segment<3>(tip).dot(a.z)),
              1e6 * std::abs(v.col(0).segment<3>(tip).dot(a.y)));
    EXPECT_GT(std::abs(v.col(1).segment<3>(tip).dot(a.y)),
              1e6 * std::abs(v.col(1).segment<3>(tip).dot(a.z)));
    // The first torsional mode: the lowest whose shape is all rotation about the
    // member axis.
    int best = -1;
    double best_share = 0;
    for (int j = 0; j < v.cols() && best < 0; ++j) {
      double twist = 0;
      for (int k = 0; k < n; ++k) {
        twist += std::pow(v.col(j).segment<3>(6 * k + 3).dot(a.x), 2);
      }
      const double share = twist / v.col(j).squaredNorm();
      if (share > 0.5) {
        best_share = share;
        best = j;
      }
    }
    ASSERT_GE(best, 0);
    EXPECT_GT(best_share, 1 - 1e-9);
    // Linear torsion elements: relative error about (pi / 2n)^2 / 24 = 2.6e-4.
    EXPECT_NEAR(f[best], f_t, 1e-3 * f_t);
    EXPECT_GT(f[best], f_t);  // consistent mass: an upper bound
  }
}

TEST(SpaceFrameElement, TimoshenkoAddsShearDeflectionAndReducesToEulerBernoulli) {
  FrameSection3d s = TestSection();
  const double l = 0.8, p = 1e5;  // short and thick: shear matters
  const Vector3d dir = Vector3d(2, -1, 1).normalized(), ref(0, 0, 1);
  const Axes a = LocalAxes(dir, ref);
  for (int n : {1, 4}) {
    SCOPED_TRACE(std::to_string(n) + " elements");
    const Line line = Cantilever(s, dir, l, n, ref, BeamTheory::kTimoshenko);
    Vector3d u, r;
    TipResponse(line, p * a.y, Vector3d::Zero(), &u, &r);
    const double bending_y = p * l * l * l / (3 * s.E * s.Iz);
    const double shear_y = p * l / (s.G * s.shear_area_y);
    EXPECT_GT(shear_y, 0.05 * bending_y);
    EXPECT_NEAR(u.dot(a.y), bending_y + shear_y, 1e-9 * (bending_y + shear_y));
    TipResponse(line, p * a.z, Vector3d::Zero(), &u, &r);
    const double z = p * l * l * l / (3 * s.E * s.Iy) + p * l / (s.G * s.shear_area_z);
    EXPECT_NEAR(u.dot(a.z), z, 1e-9 * z);
  }
  // G -> infinity: the Euler-Bernoulli deflection.
  s.G = 1e9 * s.E;
  const Line stiff = Cantilever(s, dir, l, 3, ref, BeamTheory::kTimoshenko);
  Vector3d u, r;
  TipResponse(stiff, p * a.y, Vector3d::Zero(), &u, &r);
  const double eb = p * l * l * l / (3 * s.E * s.Iz);
  EXPECT_NEAR(u.dot(a.y), eb, 1e-7 * eb);
  // And the Timoshenko matrices tend to the Euler-Bernoulli ones.
  const Matrix12 kt = Frame3dLocalStiffness(s, l, BeamTheory::kTimoshenko);
  const Matrix12 ke = Frame3dLocalStiffness(s, l);
  EXPECT_LT((kt - ke).cwiseAbs().maxCoeff(), 1e-7 * ke.cwiseAbs().maxCoeff());
  const Matrix12 mt = Frame3dLocalConsistentMass(s, l, BeamTheory::kTimoshenko);
  const Matrix12 me = Frame3dLocalConsistentMass(s, l);
  EXPECT_LT((mt - me).cwiseAbs().maxCoeff(), 1e-7 * me.cwiseAbs().maxCoeff());
}

// Rigid motion of an element's ends: translation t and small rotation w about
// the point c.
Eigen::Matrix<double, 12, 1> RigidMotion(const Vector3d& end1, const Vector3d& end2,
                                         const Vector3d& t, const Vector3d& w,
                                         const Vector3d& c) {
  Eigen::Matrix<double, 12, 1> u;
  u << t + w.cross(end1 - c), w, t + w.cross(end2 - c), w;
  return u;
}

TEST(SpaceFrameElement, RigidBodyModesAndMass) {
  const FrameSection3d s = TestSection();
  const Vector3d a(1, -2, 0.5), b(3.5, 1, 2.5), ref(0, 0, 1);
  const double l = (b - a).norm(), m = s.rho * s.A * l;
  const Axes axes = LocalAxes(b - a, ref);
  const Vector3d c = 0.5 * (a + b);
  for (BeamTheory theory : {BeamTheory::kEulerBernoulli, BeamTheory::kTimoshenko}) {
    SCOPED_TRACE(ToString(theory));
    const Matrix12 k = Frame3dStiffness(s, a, b, ref, theory);
    const Matrix12 mm = Frame3dConsistentMass(s, a, b, ref, theory);
    EXPECT_EQ(k, k.transpose());
    EXPECT_EQ(mm, mm.transpose());
    const Eigen::SelfAdjointEigenSolver<Matrix12> ek(k);
    const double top = ek.eigenvalues().maxCoeff();
    for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ek.eigenvalues()[i]), 1e-10 * top);
    EXPECT_GT(ek.eigenvalues()[6], 1e-6 * top);  // nullity exactly 6
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix12>(mm).eigenvalues().minCoeff(), 0);
    // Rigid motions carry no stiffness and the right kinetic energy.
    const Vector3d ts[] = {Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1),
                           Vector3d(0.3, -0.7, 1.1)};
    for (const Vector3d& t : ts) {
      const auto u = RigidMotion(a, b, t, Vector3d::Zero(), c);
      EXPECT_NEAR(u.dot(mm * u), m * t.squaredNorm(), 1e-12 * m);
      EXPECT_LT((k * u).norm(), 1e-9 * top);
    }
    const Vector3d ws[] = {axes.y, axes.z, axes.x, Vector3d(0.4, 0.1, -0.9)};
    for (const Vector3d& w : ws) {
      const auto u = RigidMotion(a, b, Vector3d::Zero(), w, c);
      const double normal = (w - w.dot(axes.x) * axes.x).squaredNorm();
      const double expected =
          m * l * l / 12 * normal + s.rho * s.Ip * l * std::pow(w.dot(axes.x), 2);
      EXPECT_NEAR(u.dot(mm * u), expected, 1e-12 * expected);
      EXPECT_LT((k * u).norm(), 1e-9 * top);
    }
  }
}

TEST(SpaceFrameElement, RotatingTheGeometryRotatesTheMatrices) {
  const FrameSection3d s = TestSection();
  const Vector3d a(0.2, 0.1, -0.3), b(1.7, -0.4, 2.0), ref(0.5, 1, 0);
  const Eigen::Matrix3d q =
      Eigen::AngleAxisd(0.7, Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Vector3d shift(10, -3, 4);
  Matrix12 big_q = Matrix12::Zero();
  for (int i = 0; i < 4; ++i) big_q.block<3, 3>(3 * i, 3 * i) = q;
  for (BeamTheory theory : {BeamTheory::kEulerBernoulli, BeamTheory::kTimoshenko}) {
    const Matrix12 k = Frame3dStiffness(s, a, b, ref, theory);
    const Matrix12 k2 =
        Frame3dStiffness(s, q * a + shift, q * b + shift, q * ref, theory);
    EXPECT_LT((k2 - big_q * k * big_q.transpose()).cwiseAbs().maxCoeff(),
              1e-12 * k.cwiseAbs().maxCoeff());
    const Matrix12 m = Frame3dConsistentMass(s, a, b, ref, theory);
    const Matrix12 m2 =
        Frame3dConsistentMass(s, q * a + shift, q * b + shift, q * ref, theory);
    EXPECT_LT((m2 - big_q * m * big_q.transpose()).cwiseAbs().maxCoeff(),
              1e-12 * m.cwiseAbs().maxCoeff());
  }
  const Matrix12 w = Frame3dTransverseMass(3.0, a, b, ref);
  const Matrix12 w2 = Frame3dTransverseMass(3.0, q * a, q * b, q * ref);
  EXPECT_LT((w2 - big_q * w * big_q.transpose()).cwiseAbs().maxCoeff(),
            1e-12 * w.cwiseAbs().maxCoeff());
  // The transformation is orthogonal, local x along the member.
  const Matrix12 t = Frame3dTransformation(a, b, ref);
  EXPECT_LT((t * t.transpose() - Matrix12::Identity()).norm(), 1e-14);
  EXPECT_LT((t.block<1, 3>(0, 0).transpose() - (b - a).normalized()).norm(), 1e-15);
  // Only the component of the reference normal to the member matters.
  const Matrix12 k_shifted_ref = Frame3dStiffness(s, a, b, ref + 3.0 * (b - a));
  const Matrix12 k_ref = Frame3dStiffness(s, a, b, ref);
  EXPECT_LT((k_shifted_ref - k_ref).cwiseAbs().maxCoeff(),
            1e-12 * k_ref.cwiseAbs().maxCoeff());
}

TEST(SpaceFrameElement, TransverseMassIgnoresMotionAlongTheMember) {
  const Vector3d a(0, 0, 0), b(2, 2, 1), ref(0, 0, 1);
  const double mu = 40.0, l = 3.0;
  const Matrix12 w = Frame3dTransverseMass(mu, a, b, ref);
  const Axes axes = LocalAxes(b - a, ref);
  // Translation along the member: nothing; normal to it: mu L; a twist: nothing.
  auto u_along = RigidMotion(a, b, axes.x, Vector3d::Zero(), a);
  EXPECT_NEAR(u_along.dot(w * u_along), 0.0, 1e-12);
  auto u_normal = RigidMotion(a, b, axes.z, Vector3d::Zero(), a);
  EXPECT_NEAR(u_normal.dot(w * u_normal), mu * l, 1e-12 * mu * l);
  auto u_twist = RigidMotion(a, b, Vector3d::Zero(), axes.x, a);
  EXPECT_NEAR(u_twist.dot(w * u_twist), 0.0, 1e-12);
}

TEST(SpaceFrameElement, BadInputNamesTheProblem) {
  const FrameSection3d s = TestSection();
  auto expect = [](auto call, const std::string& text) {
    try {
      call();
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  const Vector3d a(1, 1, 1), z(0, 0, 1);
  expect([&] { Frame3dStiffness(s, a, a, z); }, "ends coincide");
  expect([&] { Frame3dStiffness(s, a, a + Vector3d(0, 0, 2), z); }, "parallel");
  expect([&] { Frame3dConsistentMass(s, a, a + Vector3d(0, 0, 2), -3 * z); }, "parallel");
  expect([&] { Frame3dStiffness(s, a, a + Vector3d(1, 0, 0), Vector3d::Zero()); },
         "reference vector is zero");
  expect([&] { Frame3dLocalStiffness(s, 0.0); }, "length");
  expect([&] { Frame3dTransverseMass(0.0, a, a + z, Vector3d(1, 0, 0)); },
         "mass per length");
  const std::pair<const char*, double FrameSection3d::*> fields[] = {
      {"E", &FrameSection3d::E},   {"A", &FrameSection3d::A},
      {"Iy", &FrameSection3d::Iy}, {"Iz", &FrameSection3d::Iz},
      {"J", &FrameSection3d::J},   {"rho", &FrameSection3d::rho},
      {"G", &FrameSection3d::G},   {"Ip", &FrameSection3d::Ip}};
  for (const auto& [name, field] : fields) {
    FrameSection3d bad = s;
    bad.*field = -1;
    expect([&] { Frame3dLocalStiffness(bad, 1.0); },
           std::string("frame section.") + name);
    EXPECT_EQ(bad.Validate().field, name) << bad.Validate().ToString();
  }
  FrameSection3d bad = s;
  bad.G = 0;
  bad.nu = 0.7;
  expect([&] { Frame3dLocalConsistentMass(bad, 1.0); }, "frame section.nu");
  bad = s;
  bad.shear_area_z = 0;  // fine for Euler-Bernoulli, not for Timoshenko
  EXPECT_NO_THROW(Frame3dLocalStiffness(bad, 1.0));
  expect([&] { Frame3dLocalStiffness(bad, 1.0, BeamTheory::kTimoshenko); },
         "frame section.shear_area_z");
  expect([&] { CircularTube(1.0, 0.6, 210e9, 0.3, 7850); }, "tube.wall");
  // nu gives G when G is 0.
  bad = s;
  bad.G = 0;
  bad.nu = 0.25;
  EXPECT_DOUBLE_EQ(bad.ShearModulus(), s.E / 2.5);
  BeamTheory theory;
  EXPECT_TRUE(BeamTheoryFromString("timoshenko", &theory));
  EXPECT_EQ(theory, BeamTheory::kTimoshenko);
  EXPECT_FALSE(BeamTheoryFromString("bernoulli", &theory));
}

// ---------------------------------------------------------------------------
// The space frame.

bool SameMatrix(const SparseMatrix& a, const SparseMatrix& b, double relative) {
  const SparseMatrix d = a - b;
  double worst = 0, scale = 0;
  for (int k = 0; k < d.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(d, k); it; ++it) {
      worst = std::max(worst, std::abs(it.value()));
    }
  }
  for (int k = 0; k < a.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) {
      scale = std::max(scale, std::abs(it.value()));
    }
  }
  return worst <= relative * scale;
}

TEST(SpaceFrameBuild, CountsNamesAndSubstructures) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 2, 1, 2);
  spec.bay_width_y = 12.0;
  spec.blocks_per_level = 2;
  spec.bracing = FaceBracing::kX;
  spec.water_depth = 15.0;  // 1.5 levels
  const ParametrisedModel m = BuildSpaceFrame(spec);
  // Per level: 3 x 2 = 6 joints, 6 face panels with a centre each, members:
  // 6 legs, 2 x 2 + 1 x 3 = 7 horizontals, 6 x 4 half-diagonals = 37, each
  // with one inner node: 49 nodes.
  EXPECT_EQ(m.num_dofs(), 6 * 3 * 49);
  // Wet (midpoint below 15 m): all 37 x 2 elements of level 1; in level 2 the
  // lower element of the 6 legs and both elements of the 12 lower
  // half-diagonals.
  const SpaceFrameGeometryData g = SpaceFrameGeometry(spec);
  ASSERT_EQ(g.elements.size(), 3u * 37 * 2);
  std::set<int> wet;
  for (std::size_t i = 0; i < g.elements.size(); ++i) {
    const SpaceFrameElement& e = g.elements[i];
    const bool below = e.end1.z() + e.end2.z() < 30.0;
    EXPECT_EQ(e.wet, below);
    if (below) wet.insert(static_cast<int>(i));
  }
  EXPECT_EQ(wet.size(), 74u + 6 + 24);
  // Mass: 3; stiffness: 3 levels x 2 blocks x (legs, braces, horizontals);
  // added mass: level 1 (2 x 3) and level 2 (legs and braces, 2 blocks).
  EXPECT_EQ(m.num_parameters(), 3 + 18 + 10);
  EXPECT_EQ(m.parameter(0).name, "mass[l1]");
  EXPECT_TRUE(m.parameter(1).HasTag("wet"));
  EXPECT_TRUE(m.parameter(2).HasTag("dry"));
  EXPECT_EQ(m.parameter(3).name, "stiffness[l1:legs1]");
  EXPECT_EQ(m.parameter(4).name, "stiffness[l1:braces1]");
  EXPECT_EQ(m.parameter(5).name, "stiffness[l1:horizontals1]");
  EXPECT_EQ(m.parameter(6).name, "stiffness[l1:legs2]");
  EXPECT_EQ(m.parameter(21).name, "added_mass[l1:legs1]");
  EXPECT_GE(m.FindParameter("added_mass[l2:braces2]"), 0);
  EXPECT_LT(m.FindParameter("added_mass[l2:horizontals1]"), 0);
  EXPECT_EQ(m.dof_labels()[0], "n1:ux");
  EXPECT_EQ(m.dof_labels()[5], "n1:rz");

  const SpaceFrameSize size = SpaceFrameModelSize(spec);
  EXPECT_EQ(size.num_dofs, m.num_dofs());
  EXPECT_EQ(size.num_elements, 222);
  EXPECT_EQ(size.num_wet_elements, 104);
  EXPECT_EQ(size.num_mass_factors, 3);
  EXPECT_EQ(size.num_stiffness_factors, 18);
  EXPECT_EQ(size.num_added_mass_factors, 10);
  EXPECT_EQ(size.num_parameters, m.num_parameters());
  EXPECT_LE(m.stiffness().nonZeros(), size.nnz_bound);
  EXPECT_LE(m.mass().nonZeros(), size.nnz_bound);

  // Unique names, nonzero bases; the wet elements are exactly the added-mass
  // factors' elements, each once; every element is in one stiffness factor.
  std::set<std::string> names;
  std::multiset<int> added, stiff;
  const int n = m.num_dofs();
  SparseMatrix k_sum(n, n), m_sum(n, n);
  for (const Parameter& p : m.parameters()) {
    names.insert(p.name);
    EXPECT_GT(p.basis.local().norm(), 0.0) << p.name;
    EXPECT_FALSE(p.elements.empty()) << p.name;
    if (p.kind == ParameterKind::kAddedMass)
      added.insert(p.elements.begin(), p.elements.end());
    if (p.kind == ParameterKind::kStiffness) {
      stiff.insert(p.elements.begin(), p.elements.end());
      k_sum += p.basis.ToSparse();
    }
    if (p.kind == ParameterKind::kMass) m_sum += p.basis.ToSparse();
  }
  EXPECT_EQ(static_cast<int>(names.size()), m.num_parameters());
  EXPECT_EQ(std::set<int>(added.begin(), added.end()), wet);
  EXPECT_EQ(added.size(), wet.size());
  EXPECT_EQ(stiff.size(), g.elements.size());
  EXPECT_EQ(std::set<int>(stiff.begin(), stiff.end()).size(), g.elements.size());
  EXPECT_TRUE(SameMatrix(m.stiffness(), k_sum, 1e-12));
  EXPECT_TRUE(SameMatrix(m.mass(), m_sum, 1e-12));

  // Symmetric, positive definite.
  EXPECT_TRUE(IsSymmetric(m.stiffness(), 1e-14));
  EXPECT_TRUE(IsSymmetric(m.mass(), 1e-14));
  EXPECT_EQ(Eigen::SimplicialLLT<SparseMatrix>(m.stiffness()).info(), Eigen::Success);
  EXPECT_EQ(Eigen::SimplicialLLT<SparseMatrix>(m.mass()).info(), Eigen::Success);
}

TEST(SpaceFrameBuild, DiagonalBracingAndTimoshenkoBuild) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 3, 2, 3);
  spec.blocks_per_level = 3;
  spec.bracing = FaceBracing::kDiagonal;
  spec.theory = BeamTheory::kTimoshenko;
  const ParametrisedModel m = BuildSpaceFrame(spec);
  // Per level: 12 joints, 12 + 17 + 10 (one per face panel) = 39 members with
  // two inner nodes each.
  EXPECT_EQ(m.num_dofs(), 6 * 2 * (12 + 2 * 39));
  EXPECT_EQ(m.num_parameters(), 2 + 2 * 3 * 3);  // dry: no added mass
  EXPECT_EQ(SpaceFrameModelSize(spec).num_parameters, m.num_parameters());
  EXPECT_EQ(Eigen::SimplicialLLT<SparseMatrix>(m.stiffness()).info(), Eigen::Success);
  // No bracing: no "braces" factors.
  spec.bracing = FaceBracing::kNone;
  const ParametrisedModel bare = BuildSpaceFrame(spec);
  EXPECT_EQ(bare.num_parameters(), 2 + 2 * 3 * 2);
  EXPECT_LT(bare.FindParameter("stiffness[l1:braces1]"), 0);
  FaceBracing b;
  EXPECT_TRUE(FaceBracingFromString("x", &b));
  EXPECT_EQ(b, FaceBracing::kX);
  EXPECT_STREQ(ToString(FaceBracing::kDiagonal), "diagonal");
}

// u' M u for a unit translation t of every free node: every element's mass,
// less what the clamped base keeps of the elements touching it (an element
// with one end held, the other moved by t, has kinetic energy
// m ((t.d)^2 / 3 + |t x d|^2 156 / 420), d its unit axis).
double BaseShare(const Vector3d& t, const Vector3d& d) {
  const double along = std::pow(t.dot(d), 2);
  return along / 3 + (t.squaredNorm() - along) * 156.0 / 420.0;
}

Eigen::VectorXd Translation(int n, int direction) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  for (int i = direction; i < n; i += 6) u[i] = 1.0;
  return u;
}

TEST(SpaceFrameBuild, TotalMassIsTheSumOfMemberMasses) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(4, 2, 1, 3, 10.0, 15.0, 12.0);
  spec.bracing = FaceBracing::kDiagonal;
  const ParametrisedModel m = BuildSpaceFrame(spec);
  const double h = 10, wx = 15, wy = 12, e = 3;
  const double mu_leg = spec.legs.rho * spec.legs.A;
  const double mu_hor = spec.horizontals.rho * spec.horizontals.A;
  const double mu_br = spec.braces.rho * spec.braces.A;
  const double dx = std::hypot(wx, h), dy = std::hypot(wy, h);
  // Per level: 6 legs, 2 x 2 horizontals along X and 3 x 1 along Y, one
  // diagonal in each of 2 x 2 panels of the X faces and 2 x 1 of the Y faces.
  const double level =
      6 * mu_leg * h + (4 * wx + 3 * wy) * mu_hor + (4 * dx + 2 * dy) * mu_br;
  const double total = 4 * level;
  for (int dir = 0; dir < 3; ++dir) {
    SCOPED_TRACE("direction " + std::to_string(dir));
    const Vector3d t = Vector3d::Unit(dir);
    // At the base: 6 leg elements along Z, 4 diagonal elements in the X faces
    // along (+-wx, 0, h), 2 in the Y faces along (0, +-wy, h).
    const double kept = 6 * mu_leg * h / e * (1 - BaseShare(t, Vector3d(0, 0, 1))) +
                        2 * mu_br * dx / e *
                            (2 - BaseShare(t, Vector3d(wx, 0, h) / dx) -
                             BaseShare(t, Vector3d(-wx, 0, h) / dx)) +
                        2 * mu_br * dy / e * (1 - BaseShare(t, Vector3d(0, wy, h) / dy));
    const Eigen::VectorXd u = Translation(m.num_dofs(), dir);
    EXPECT_NEAR(u.dot(m.mass() * u), total - kept, 1e-12 * total);
  }
}

TEST(SpaceFrameBuild, AddedMassActsOnWetMembersTransversely) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 2, 1, 2);
  spec.level_height = 10.0;
  spec.bay_width_y = 12.0;
  spec.bracing = FaceBracing::kNone;
  spec.water_depth = 15.0;
  const ParametrisedModel m = BuildSpaceFrame(spec);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.num_parameters());
  const SparseMatrix ma = m.AddedMass(ones);
  const double mu_leg = spec.legs.rho * spec.legs.A;
  const double mu_hor = spec.horizontals.rho * spec.horizontals.A;
  // X translation: the 6 legs' elements below 15 m (the base ones keep
  // 156/420 of their share) and the 3 wet horizontals along Y at 10 m; the
  // 4 along X move axially and carry none.
  const Eigen::VectorXd ux = Translation(m.num_dofs(), 0);
  EXPECT_NEAR(ux.dot(ma * ux), 6 * mu_leg * 5 * (156.0 / 420 + 2) + 3 * mu_hor * 12,
              1e-12 * ux.dot(ma * ux));
  // Y: the legs again and the 4 horizontals along X (15 m each).
  const Eigen::VectorXd uy = Translation(m.num_dofs(), 1);
  EXPECT_NEAR(uy.dot(ma * uy), 6 * mu_leg * 5 * (156.0 / 420 + 2) + 4 * mu_hor * 15,
              1e-12 * uy.dot(ma * uy));
  // Z: only the wet horizontals, all 7.
  const Eigen::VectorXd uz = Translation(m.num_dofs(), 2);
  EXPECT_NEAR(uz.dot(ma * uz), (3 * 12 + 4 * 15) * mu_hor, 1e-12 * uz.dot(ma * uz));
}

// The Structure the diagnosis acts on (BuildSpaceFrameStructure) is the
// generator's own grouping: its elements sum to the model's K and M, each
// element's stiffness is its stiffness factor's basis, a level's elements'
// masses sum to that level's mass basis and the wet ones carry their added-mass
// factor's basis.
TEST(SpaceFrameStructure, ElementsSumToTheModelAndMatchItsFactors) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 2, 1, 2);
  spec.bay_width_y = 12.0;
  spec.blocks_per_level = 2;
  spec.water_depth = 15.0;
  const ParametrisedModel m = BuildSpaceFrame(spec);
  const Structure s = BuildSpaceFrameStructure(spec);
  EXPECT_EQ(s.type, "space_frame");
  ASSERT_EQ(s.dof_labels, m.dof_labels());
  auto max_abs = [](const SparseMatrix& a) {
    double x = 0;
    for (int j = 0; j < a.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a, j); it; ++it)
        x = std::max(x, std::abs(it.value()));
    return x;
  };
  const double k_scale = max_abs(m.stiffness());
  const double m_scale = max_abs(m.mass());
  EXPECT_LT(max_abs(s.stiffness - m.stiffness()), 1e-12 * k_scale);
  EXPECT_LT(max_abs(s.mass - m.mass()), 1e-12 * m_scale);
  const int n = m.num_dofs();
  SparseMatrix k_sum(n, n), m_sum(n, n);
  std::vector<SparseMatrix> level_mass(spec.levels, SparseMatrix(n, n));
  int wet = 0;
  const std::vector<int> stiffness = m.ParametersOfKind(ParameterKind::kStiffness);
  ASSERT_EQ(s.elements.size(), stiffness.size());
  for (std::size_t i = 0; i < s.elements.size(); ++i) {
    const ElementMatrices& e = s.elements[i];
    EXPECT_EQ(e.id, static_cast<int>(i) + 1);
    EXPECT_EQ("stiffness[" + e.label + "]", m.parameter(stiffness[i]).name);
    EXPECT_LT(max_abs(e.stiffness - m.parameter(stiffness[i]).basis.ToSparse()),
              1e-12 * k_scale);
    k_sum += e.stiffness;
    m_sum += e.mass;
    const int level = std::stoi(e.label.substr(1, e.label.find(':') - 1));
    EXPECT_DOUBLE_EQ(e.x0, (level - 1) * spec.level_height);
    EXPECT_DOUBLE_EQ(e.x1, level * spec.level_height);
    level_mass[level - 1] += e.mass;
    const int w = m.FindParameter("added_mass[" + e.label + "]");
    EXPECT_EQ(e.wet, w >= 0) << e.label;
    if (w >= 0) {
      ++wet;
      EXPECT_LT(max_abs(e.added_mass_basis - m.parameter(w).basis.ToSparse()),
                1e-12 * m_scale);
    } else {
      EXPECT_EQ(e.added_mass_basis.nonZeros(), 0) << e.label;
    }
  }
  EXPECT_EQ(wet, static_cast<int>(m.ParametersOfKind(ParameterKind::kAddedMass).size()));
  EXPECT_GT(wet, 0);
  EXPECT_LT(max_abs(k_sum - m.stiffness()), 1e-12 * k_scale);
  EXPECT_LT(max_abs(m_sum - m.mass()), 1e-12 * m_scale);
  for (int level = 1; level <= spec.levels; ++level) {
    const int p = m.FindParameter("mass[l" + std::to_string(level) + "]");
    ASSERT_GE(p, 0);
    EXPECT_LT(max_abs(level_mass[level - 1] - m.parameter(p).basis.ToSparse()),
              1e-12 * m_scale);
  }
  // Its form variant is the generator's Timoshenko frame; a Timoshenko frame
  // has none.
  ASSERT_EQ(s.form_variants.size(), 1u);
  SpaceFrameSpec sheared = spec;
  sheared.theory = BeamTheory::kTimoshenko;
  const ParametrisedModel t = BuildSpaceFrame(sheared);
  EXPECT_LT(max_abs(s.form_variants[0].stiffness - t.stiffness()), 1e-12 * k_scale);
  EXPECT_LT(max_abs(s.form_variants[0].mass - t.mass()), 1e-12 * m_scale);
  EXPECT_GT(max_abs(s.form_variants[0].stiffness - s.stiffness), 1e-6 * k_scale);
  EXPECT_TRUE(BuildSpaceFrameStructure(sheared).form_variants.empty());
  // Nodes with their coordinates; attached masses looked for at the six
  // joints of the top level only.
  ASSERT_EQ(6 * s.nodes.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(s.nodes[0].name, "n1");
  EXPECT_TRUE(s.nodes[0].xyz.isApprox(Eigen::Vector3d(0, 0, 10)));
  ASSERT_EQ(s.attached_mass_nodes.size(), 6u);
  for (const std::string& name : s.attached_mass_nodes) {
    const auto at =
        std::find_if(s.nodes.begin(), s.nodes.end(),
                     [&](const ModelNode& node) { return node.name == name; });
    ASSERT_NE(at, s.nodes.end());
    EXPECT_DOUBLE_EQ(at->xyz.z(), 30.0) << name;
  }
}

TEST(SpaceFrameModes, SparseShiftInvertMatchesDense) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 2, 1, 2);
  spec.bay_width_y = 11.0;
  spec.water_depth = 8.0;
  const ParametrisedModel m = BuildSpaceFrame(spec);
  ASSERT_EQ(m.num_dofs(), 6 * 2 * 49);
  EigenOptions dense;
  dense.method = EigenOptions::Method::kDense;
  EigenOptions sparse;
  sparse.method = EigenOptions::Method::kSparseShiftInvert;
  sparse.num_modes = 8;
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(m.num_parameters(), 0.1);
  for (const SparseMatrix& mass : {m.mass(), m.UpdatedWetMass(d)}) {
    const Modes a = SolveModes(m.stiffness(), mass, dense);
    const Modes b = SolveModes(m.stiffness(), mass, sparse);
    ASSERT_EQ(b.size(), 8);
    for (int i = 0; i < 8; ++i) {
      EXPECT_NEAR(b.eigenvalues[i], a.eigenvalues[i], 1e-8 * a.eigenvalues[i]);
      EXPECT_GT(Mac(a.shapes.col(i), b.shapes.col(i)), 1 - 1e-8) << "mode " << i;
    }
  }
}

TEST(SpaceFrameModes, SquareFrameSwaysEquallyInXAndY) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(4, 2, 2, 2);
  const ParametrisedModel m = BuildSpaceFrame(spec);
  EigenOptions options;
  options.method = EigenOptions::Method::kSparseShiftInvert;
  options.num_modes = 4;
  const Modes modes = SolveModes(m.stiffness(), m.mass(), options);
  const Eigen::VectorXd& lambda = modes.eigenvalues;
  EXPECT_NEAR(lambda[1], lambda[0], 1e-8 * lambda[0]);
  EXPECT_GT(lambda[2], 1.05 * lambda[1]);
  // The pair carries equal effective mass in X and in Y, a good part of it.
  const Eigen::VectorXd ux = Translation(m.num_dofs(), 0);
  const Eigen::VectorXd uy = Translation(m.num_dofs(), 1);
  double gx = 0, gy = 0;
  for (int i = 0; i < 2; ++i) {
    gx += std::pow(modes.shapes.col(i).dot(m.mass() * ux), 2);
    gy += std::pow(modes.shapes.col(i).dot(m.mass() * uy), 2);
  }
  EXPECT_NEAR(gx, gy, 1e-6 * gx);
  EXPECT_GT(gx, 0.3 * ux.dot(m.mass() * ux));
}

// A member's finite elements (ElementMember::parts): what damage over part of
// its length acts on. Their spans tile the member from its first joint, their
// stiffnesses sum to the member's, and their heights are their elements'. A
// member of one element has no parts.
TEST(SpaceFrameStructure, MemberPartsTileTheirMember) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2, 10, 12, 12);
  spec.bracing = FaceBracing::kX;
  const Structure s = BuildSpaceFrameStructure(spec);
  for (const ElementMember& m : s.members) {
    ASSERT_EQ(m.parts.size(), 2u) << m.label;
    EXPECT_NEAR(m.parts[0].from, 0.0, 1e-12);
    EXPECT_NEAR(m.parts[0].to, 0.5, 1e-12);
    EXPECT_NEAR(m.parts[1].from, 0.5, 1e-12);
    EXPECT_NEAR(m.parts[1].to, 1.0, 1e-12);
    const Eigen::MatrixXd whole = Eigen::MatrixXd(m.stiffness.ToSparse());
    const Eigen::MatrixXd d = Eigen::MatrixXd(m.parts[0].stiffness.ToSparse() +
                                              m.parts[1].stiffness.ToSparse()) -
                              whole;
    EXPECT_LT(d.cwiseAbs().maxCoeff(), 1e-12 * whole.cwiseAbs().maxCoeff()) << m.label;
    EXPECT_GT(m.parts[0].stiffness.ToSparse().norm(), 0.0);
  }
  // brace n1-n17 runs from n1 (z 10) to the face centre n17 (z 15).
  const auto brace =
      std::find_if(s.members.begin(), s.members.end(),
                   [](const ElementMember& m) { return m.label == "brace n1-n17"; });
  ASSERT_NE(brace, s.members.end());
  EXPECT_DOUBLE_EQ(brace->parts[0].x0, 10.0);
  EXPECT_DOUBLE_EQ(brace->parts[0].x1, 12.5);
  EXPECT_DOUBLE_EQ(brace->parts[1].x0, 12.5);
  EXPECT_DOUBLE_EQ(brace->parts[1].x1, 15.0);
  spec.elements_per_member = 1;
  for (const ElementMember& m : BuildSpaceFrameStructure(spec).members)
    EXPECT_TRUE(m.parts.empty()) << m.label;
}

// Each member of the frame, on its own (Structure::members): what a stiffness
// loss of one brace acts on. The members of a group sum to its stiffness, are
// named by kind and end joints, and each one's stiffness is its own: an axial
// stretch of an inclined brace (its nodes moved along its axis in proportion
// to their distance from its first end, no rotation) stores E A d^2 / L, and a
// rigid translation stores nothing.
TEST(SpaceFrameStructure, MembersSumToTheirGroupsAndStretchAsBars) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2, 10, 12, 12);
  spec.bracing = FaceBracing::kX;
  const Structure s = BuildSpaceFrameStructure(spec);
  // Per level: 4 legs, 4 horizontals and 4 faces of 4 half braces.
  ASSERT_EQ(s.members.size(), 3u * 24u);
  std::set<std::string> labels;
  std::vector<SparseMatrix> sum(s.elements.size(),
                                SparseMatrix(s.stiffness.rows(), s.stiffness.cols()));
  for (const ElementMember& m : s.members) {
    EXPECT_TRUE(labels.insert(m.label).second) << m.label;
    ASSERT_GE(m.element, 0);
    sum[static_cast<std::size_t>(m.element)] += m.stiffness.ToSparse();
    EXPECT_LE(m.x0, m.x1);
  }
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const Eigen::MatrixXd d = Eigen::MatrixXd(sum[e] - s.elements[e].stiffness);
    EXPECT_LT(d.cwiseAbs().maxCoeff(),
              1e-12 * Eigen::MatrixXd(s.elements[e].stiffness).cwiseAbs().maxCoeff())
        << s.elements[e].label;
  }
  EXPECT_TRUE(labels.count("leg b1-n1"));  // from the base joint b1, clamped
  EXPECT_TRUE(labels.count("horizontal n1-n2"));
  EXPECT_TRUE(labels.count("brace b1-n13"));  // the level-1 X's bottom corners to
  EXPECT_TRUE(labels.count("brace b2-n13"));  // its centre
  EXPECT_TRUE(labels.count("brace n1-n17"));
  EXPECT_TRUE(labels.count("brace n17-n6"));  // the centre to a top corner
  const auto brace =
      std::find_if(s.members.begin(), s.members.end(),
                   [](const ElementMember& m) { return m.label == "brace n1-n17"; });
  ASSERT_NE(brace, s.members.end());
  EXPECT_EQ(s.elements[static_cast<std::size_t>(brace->element)].label, "l2:braces1");
  EXPECT_DOUBLE_EQ(brace->x0, 10.0);
  EXPECT_DOUBLE_EQ(brace->x1, 15.0);
  // n1 = (0, 0, 10), n17 = the centre of the face y = 0 = (6, 0, 15).
  const Vector3d a(0, 0, 10), b(6, 0, 15);
  const double length = (b - a).norm(), d = 1e-3;
  const int n = static_cast<int>(s.stiffness.rows());
  Eigen::VectorXd stretch = Eigen::VectorXd::Zero(n), shift = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < s.nodes.size(); ++k) {
    const Vector3d& p = s.nodes[k].xyz;
    const double t = (p - a).dot(b - a) / (length * length);
    const bool on = (p - a - t * (b - a)).norm() < 1e-9 && t > -1e-9 && t < 1 + 1e-9;
    if (!on) continue;
    stretch.segment<3>(6 * static_cast<Eigen::Index>(k)) = t * d * (b - a) / length;
    shift.segment<3>(6 * static_cast<Eigen::Index>(k)) = Vector3d(1, 2, 3);
  }
  const SparseMatrix k = brace->stiffness.ToSparse();
  const double ea = spec.braces.E * spec.braces.A;
  EXPECT_NEAR(stretch.dot(k * stretch), ea * d * d / length, 1e-9 * ea * d * d / length);
  EXPECT_LT(std::abs(shift.dot(k * shift)), 1e-9 * ea / length);
  // On base springs, the same names.
  spec.base.horizontal = 1e9;
  const Structure sprung = BuildSpaceFrameStructure(spec);
  ASSERT_EQ(sprung.members.size(), s.members.size());
  for (std::size_t i = 0; i < s.members.size(); ++i)
    EXPECT_EQ(sprung.members[i].label, s.members[i].label);
}

// Springs under the legs (SpaceFrameBase): each base joint "b<k>" gets the
// sprung DOFs after every free node's, whose labels stay as on the clamped
// frame; the springs are in K (not in any factor) and are the Structure's
// supports. On a frame whose members are 10^4 times stiffer than steel the
// structure moves as a rigid body on its springs: on horizontal springs alone
// it sways at omega^2 = 4 k_h / M and on vertical springs alone it bounces at
// 4 k_v / M (M the total mass, four legs), to the frame's own flexibility
// (about 1e-6 here). Very stiff springs give the clamped frame's frequencies.
TEST(SpaceFrameBuild, BaseSpringsAddDofsAndSupportTheLegs) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 1, 1, 2, 10, 12, 12);
  const ParametrisedModel clamped = BuildSpaceFrame(spec);
  spec.base.horizontal = 2e8;
  spec.base.rocking = 5e9;
  const ParametrisedModel sprung = BuildSpaceFrame(spec);
  ASSERT_EQ(sprung.num_dofs(), clamped.num_dofs() + 4 * 4);
  EXPECT_EQ(SpaceFrameModelSize(spec).num_dofs, sprung.num_dofs());
  for (int i = 0; i < clamped.num_dofs(); ++i)
    EXPECT_EQ(sprung.dof_labels()[i], clamped.dof_labels()[i]);
  const std::vector<std::string> b1(sprung.dof_labels().begin() + clamped.num_dofs(),
                                    sprung.dof_labels().begin() + clamped.num_dofs() + 4);
  EXPECT_EQ(b1, (std::vector<std::string>{"b1:ux", "b1:uy", "b1:rx", "b1:ry"}));
  EXPECT_EQ(sprung.dof_labels().back(), "b4:ry");
  EXPECT_EQ(sprung.num_parameters(), clamped.num_parameters());
  // The Structure: the same K and M, the springs as supports, the base nodes.
  const Structure s = BuildSpaceFrameStructure(spec);
  EXPECT_EQ(s.dof_labels, sprung.dof_labels());
  EXPECT_LT((Eigen::MatrixXd(s.stiffness) - Eigen::MatrixXd(sprung.stiffness())).norm(),
            1e-9 * Eigen::MatrixXd(sprung.stiffness()).norm());
  EXPECT_EQ(s.dof_positions.size(), s.dof_labels.size());
  ASSERT_EQ(s.supports.size(), 16u);
  EXPECT_EQ(s.supports[0].name, "base horizontal X at b1");
  EXPECT_EQ(s.supports[0].unit, "N/m");
  EXPECT_EQ(s.supports[3].name, "base rocking about Y at b1");
  EXPECT_EQ(s.supports[3].unit, "N m/rad");
  EXPECT_EQ(s.supports[3].stiffness, 5e9);
  EXPECT_EQ(s.supports[3].dof, sprung.FindDof("b1:ry"));
  EXPECT_NE(s.description.find("on base springs (horizontal 2e+08 N/m, rocking 5e+09"),
            std::string::npos)
      << s.description;
  for (const LineSegment& g : s.segments) EXPECT_GE(g.node_a, 0);  // no clamped end
  EXPECT_EQ(s.nodes.back().name, "b4");
  EXPECT_TRUE(s.nodes.back().xyz.isApprox(Vector3d(12, 12, 0)));
  ASSERT_EQ(s.form_variants.size(), 1u);
  EXPECT_EQ(s.form_variants[0].stiffness.rows(), sprung.num_dofs());

  // Softer springs lower every frequency; very stiff ones give the clamped
  // frame's.
  EigenOptions dense;
  dense.method = EigenOptions::Method::kDense;
  const Eigen::VectorXd f0 =
      SolveModes(clamped.stiffness(), clamped.mass(), dense).FrequenciesHz();
  const Eigen::VectorXd f1 =
      SolveModes(sprung.stiffness(), sprung.mass(), dense).FrequenciesHz();
  for (int j = 0; j < 8; ++j) EXPECT_LT(f1[j], f0[j]) << j;
  spec.base.horizontal = spec.base.rocking = 1e17;
  const ParametrisedModel stiff = BuildSpaceFrame(spec);
  const Eigen::VectorXd f2 =
      SolveModes(stiff.stiffness(), stiff.mass(), dense).FrequenciesHz();
  for (int j = 0; j < 8; ++j) EXPECT_NEAR(f2[j] / f0[j], 1.0, 1e-6) << j;

  // A rigid frame on horizontal, then on vertical springs.
  for (const bool horizontal : {true, false}) {
    SCOPED_TRACE(horizontal);
    SpaceFrameSpec rigid = fixtures::SpaceFrame(2, 1, 1, 2, 10, 12, 12);
    for (FrameSection3d* sec : {&rigid.legs, &rigid.braces, &rigid.horizontals})
      sec->E *= 1e4;
    const double k = 1e6;
    (horizontal ? rigid.base.horizontal : rigid.base.vertical) = k;
    const ParametrisedModel m = BuildSpaceFrame(rigid);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(m.num_dofs());
    const std::string dir = horizontal ? ":ux" : ":uz";
    for (int i = 0; i < m.num_dofs(); ++i)
      if (m.dof_labels()[i].size() > 3 &&
          m.dof_labels()[i].substr(m.dof_labels()[i].size() - 3) == dir)
        u[i] = 1.0;
    const double total_mass = u.dot(m.mass() * u);
    const Modes modes = SolveModes(m.stiffness(), m.mass(), dense);
    const double omega2 = 4 * k / total_mass;
    // The lowest modes (x and y sway, of one eigenvalue, or the bounce) are
    // the rigid body's: their eigenvalue, and they span its motion.
    const int rigid_modes = horizontal ? 2 : 1;
    double spanned = 0;
    for (int j = 0; j < rigid_modes; ++j) {
      EXPECT_NEAR(modes.eigenvalues[j] / omega2, 1.0, 1e-5) << j;
      spanned += std::pow(modes.shapes.col(j).dot(m.mass() * u), 2) / total_mass;
    }
    EXPECT_NEAR(spanned, 1.0, 1e-5);
    EXPECT_GT(modes.eigenvalues[rigid_modes], 100 * omega2);
  }
}

// A clamped frame's base joints are rigid supports (what support flexibility
// releases where the frame has no springs): the coupling of each joint's six
// restrained directions to the frame, and among them, is what the same frame
// on springs in every direction has on that joint's base DOFs, less the
// springs.
TEST(SpaceFrameStructure, ClampedBaseJointsAreRigidSupports) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 1, 1, 2, 10, 12, 12);
  const Structure clamped = BuildSpaceFrameStructure(spec);
  ASSERT_EQ(clamped.rigid_supports.size(), 4u);
  EXPECT_TRUE(clamped.supports.empty());
  spec.base = {2e8, 3e9, 5e9, 7e9};  // horizontal, vertical, rocking, torsion
  const Structure sprung = BuildSpaceFrameStructure(spec);
  ASSERT_TRUE(sprung.rigid_supports.empty());
  const Eigen::MatrixXd k(sprung.stiffness), m(sprung.mass);
  const double springs[6] = {2e8, 2e8, 3e9, 5e9, 5e9, 7e9};
  const char* const dirs[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const int n = static_cast<int>(clamped.dof_labels.size());
  for (const RigidSupport& sp : clamped.rigid_supports) {
    SCOPED_TRACE(sp.name);
    ASSERT_EQ(sp.directions.size(), 6u);
    std::vector<int> base;
    for (const char* d : dirs) {
      const auto at = std::find(sprung.dof_labels.begin(), sprung.dof_labels.end(),
                                sp.name + ":" + d);
      ASSERT_NE(at, sprung.dof_labels.end());
      base.push_back(static_cast<int>(at - sprung.dof_labels.begin()));
    }
    const double scale = k.cwiseAbs().maxCoeff(), mass_scale = m.cwiseAbs().maxCoeff();
    for (int a = 0; a < 6; ++a) {
      for (int b = 0; b < 6; ++b) {
        EXPECT_NEAR(sp.k_bb(a, b) + (a == b ? springs[a] : 0.0), k(base[a], base[b]),
                    1e-12 * scale);
        EXPECT_NEAR(sp.m_bb(a, b), m(base[a], base[b]), 1e-12 * mass_scale);
      }
      for (int i = 0; i < n; ++i) {
        const auto row = std::find(sp.rows.begin(), sp.rows.end(), i);
        const bool coupled = row != sp.rows.end();
        const int r = static_cast<int>(row - sp.rows.begin());
        EXPECT_NEAR(coupled ? sp.k_fb(r, a) : 0.0, k(i, base[a]), 1e-12 * scale) << i;
        EXPECT_NEAR(coupled ? sp.m_fb(r, a) : 0.0, m(i, base[a]), 1e-12 * mass_scale)
            << i;
      }
    }
  }
}

TEST(SpaceFrameInput, BadSpecNamesTheField) {
  auto expect = [](const SpaceFrameSpec& spec, const std::string& field) {
    for (int call = 0; call < 3; ++call) {
      try {
        if (call == 0) BuildSpaceFrame(spec);
        if (call == 1) SpaceFrameModelSize(spec);
        if (call == 2) SpaceFrameGeometry(spec);
        ADD_FAILURE() << "no error for " << field;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("model." + field), std::string::npos)
            << e.what();
      }
    }
    EXPECT_EQ(spec.Validate().field, field) << spec.Validate().ToString();
  };
  SpaceFrameSpec s;
  s.levels = 0;
  expect(s, "levels");
  s = {};
  s.levels = 100000;
  expect(s, "levels");  // too many DOFs
  s = {};
  s.bays_x = 0;
  expect(s, "bays_x");
  s = {};
  s.bays_y = -1;
  expect(s, "bays_y");
  s = {};
  s.level_height = 0;
  expect(s, "level_height");
  s = {};
  s.bay_width_x = NAN;
  expect(s, "bay_width_x");
  s = {};
  s.bay_width_y = -2;
  expect(s, "bay_width_y");
  s = {};
  s.elements_per_member = 0;
  expect(s, "elements_per_member");
  s = {};
  s.blocks_per_level = 3;  // bays_x = 2
  expect(s, "blocks_per_level");
  s = {};
  s.bracing = static_cast<FaceBracing>(7);
  expect(s, "bracing");
  s = {};
  s.water_depth = -1;
  expect(s, "water_depth");
  s = {};
  s.theory = static_cast<BeamTheory>(5);
  expect(s, "theory");
  s = {};
  s.base.rocking = -1;
  expect(s, "base.rocking");
  s = {};
  s.base.vertical = NAN;
  expect(s, "base.vertical");
  s = {};
  s.legs.Iy = 0;
  expect(s, "legs.Iy");
  s = {};
  s.braces.E = -1;
  expect(s, "braces.E");
  s = {};
  s.horizontals.J = INFINITY;
  expect(s, "horizontals.J");
  s = {};
  s.horizontals.G = 0;
  s.horizontals.nu = -2;
  expect(s, "horizontals.nu");
  s = {};
  s.theory = BeamTheory::kTimoshenko;
  s.legs.shear_area_y = 0;
  expect(s, "legs.shear_area_y");
  s = {};
  EXPECT_EQ(s.Validate().ToString(), "");
}

}  // namespace
}  // namespace femup
