#include "femup/problems/model_effects.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "femup/core/errors.h"
#include "femup/core/fe/beam_modifications.h"
#include "femup/core/fe/dof_labels.h"
#include "femup/core/fe/sensor.h"
#include "vector_of.h"

namespace femup {

namespace {

using internal::VectorOf;

SparseMatrix Zero(int n) { return SparseMatrix(n, n); }

// The largest stiffness loss a stated prior may reach (all of it leaves a
// mechanism).
constexpr double kMaxLoss = 0.99;

bool IsTranslation(const std::string& component) {
  return component.empty() || component == "ux" || component == "uy" || component == "uz";
}

bool IsRotation(const std::string& component) {
  return component == "rx" || component == "ry" || component == "rz";
}

// The unit axes along which (kind 'u') or about which (kind 'r') the model has
// DOFs anywhere ("n3:uy", "n3:rz"), in x, y, z order.
std::vector<Eigen::Vector3d> AxesWithDofs(const Structure& s, char kind) {
  std::vector<Eigen::Vector3d> axes;
  for (int k = 0; k < 3; ++k) {
    const std::string tail = std::string(":") + kind + "xyz"[k];
    for (const std::string& l : s.dof_labels) {
      if (l.size() > tail.size() &&
          l.compare(l.size() - tail.size(), tail.size(), tail) == 0) {
        axes.push_back(Eigen::Vector3d::Unit(k));
        break;
      }
    }
  }
  return axes;
}

// Elements whose positions along the structure are heights (x0 < x1 in m).
bool HasHeights(const Structure& s) {
  if (s.type != "cantilever" || s.elements.empty()) return false;
  return std::all_of(s.elements.begin(), s.elements.end(),
                     [](const ElementMatrices& e) { return e.x1 > e.x0; });
}

bool HasElementMatrices(const Structure& s) {
  return !s.elements.empty() &&
         std::all_of(s.elements.begin(), s.elements.end(), [&](const ElementMatrices& e) {
           return e.stiffness.rows() == static_cast<Eigen::Index>(s.dof_labels.size());
         });
}

class Base : public ModelEffect {
 public:
  Base(const Structure& s, EffectRegion region) : s_(s), region_(std::move(region)) {}
  const EffectRegion& region() const override { return region_; }

 protected:
  int n() const { return static_cast<int>(s_.dof_labels.size()); }
  // The span from the first element's start to the last one's end.
  EffectLocation WholeLength() const {
    EffectLocation l;
    l.x0 = s_.elements.front().x0;
    l.x1 = s_.elements.back().x1;
    return l;
  }
  const Structure& s_;
  EffectRegion region_;
};

// Every element's stiffness times s = exp(theta_0).
class MaterialScaling : public Base {
 public:
  MaterialScaling(const Structure& s, EffectRegion region) : Base(s, std::move(region)) {
    sum_ = Zero(n());
    for (int e : region_.elements) sum_ += s_.elements[e].stiffness;
  }
  std::string kind() const override { return "material_scaling"; }
  std::vector<EffectParameter> Parameters() const override {
    return {LogQuantity({"ln_e_factor", "ln(E_real / E_model)", -0.7, 0.7, false},
                        "factor", 1.0)};
  }
  std::vector<Eigen::VectorXd> Starts() const override { return {VectorOf({0.0})}; }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return {(std::exp(t[0]) - 1.0) * sum_, {}};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int, Immersion) const override {
    return {std::exp(t[0]) * sum_, {}};
  }
  EffectLocation Location(const Eigen::VectorXd&) const override { return WholeLength(); }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    return {{"e_factor", "1", std::exp(t[0])}};
  }

 private:
  SparseMatrix sum_;
};

// A uniform axial force along a cantilever (a riser's or tendon's tension, a
// pile's compression), as a fraction p of the model's own buckling load N_cr
// (pi^2 E I / (4 L^2) for a uniform clamped bar): dK = p N_cr K_G, K_G the
// geometric stiffness of a unit tension on every element (beam_modifications.h).
// Linear in p, from 0.8 of the buckling load in compression (K stays positive
// definite with other effects softening the bar a little) to 10 times it in
// tension, as on the cantilever's own pipeline (effects.h). Not tried unless a
// study names it: a load is known to whoever applies it.
class AxialLoad : public Base {
 public:
  static constexpr double kMaxCompression = 0.8;
  static constexpr double kMaxTension = 10.0;
  AxialLoad(const Structure& s, EffectRegion region)
      : Base(s, std::move(region)), unit_(AxialForceStiffness(s, 1.0)) {
    buckling_ = BucklingLoad(s.stiffness, unit_);
  }
  std::string kind() const override { return "axial_load"; }
  std::vector<EffectParameter> Parameters() const override {
    return {LinearQuantity({"force_ratio",
                            "axial force / the model's buckling load, tension positive, "
                            "compression negative",
                            -kMaxCompression, kMaxTension, false},
                           "force_n", buckling_, -kMaxCompression * buckling_,
                           std::numeric_limits<double>::infinity())};
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    return {VectorOf({0.0}), VectorOf({-0.4}), VectorOf({2.0})};
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return {(t[0] * buckling_) * unit_, {}};
  }
  ModelChange Derivative(const Eigen::VectorXd&, int, Immersion) const override {
    return {buckling_ * unit_, {}};
  }
  EffectLocation Location(const Eigen::VectorXd&) const override { return WholeLength(); }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    return {{"axial_force", "N", t[0] * buckling_},
            {"force_ratio", "1", t[0]},
            {"buckling_load", "N", buckling_}};
  }
  // The compression N_cr at which K - N_cr K_G turns singular: 1 / the largest
  // eigenvalue of K_G x = mu K x (dense; a cantilever's few hundred DOFs).
  static double BucklingLoad(const SparseMatrix& k, const SparseMatrix& unit) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
        Eigen::MatrixXd(unit), Eigen::MatrixXd(k), Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success || !(eig.eigenvalues().maxCoeff() > 0)) {
      throw InputError("effect",
                       "axial_load: the model's buckling load could not be found "
                       "(its stiffness is not positive definite, or no element "
                       "bends under an axial force)");
    }
    return 1.0 / eig.eigenvalues().maxCoeff();
  }

 private:
  SparseMatrix unit_;
  double buckling_ = 0;
};

// One element's stiffness (or one member's of a group element) times 1 - loss,
// loss = exp(theta_0).
class StiffnessLoss : public Base {
 public:
  // An element's: its own stiffness matrix, kept by reference.
  StiffnessLoss(const Structure& s, EffectRegion region, const ElementMatrices& element)
      : Base(s, std::move(region)),
        stiffness_(&element.stiffness),
        x0_(element.x0),
        x1_(element.x1) {}
  // A member's: its stiffness held here.
  StiffnessLoss(const Structure& s, EffectRegion region, const ElementMember& member)
      : Base(s, std::move(region)),
        own_(member.stiffness.ToSparse()),
        stiffness_(&own_),
        x0_(member.x0),
        x1_(member.x1) {}
  // A member's instance points at its own matrix: a copy would point at the
  // original's.
  StiffnessLoss(const StiffnessLoss&) = delete;
  StiffnessLoss& operator=(const StiffnessLoss&) = delete;
  std::string kind() const override { return "stiffness_loss"; }
  std::vector<EffectParameter> Parameters() const override {
    return {LogQuantity({"ln_loss", "ln(fraction of the stiffness lost)", std::log(3e-3),
                         std::log(0.9), false},
                        "loss", 1.0, kMaxLoss)};
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    return {VectorOf({std::log(0.03)}), VectorOf({std::log(0.3)})};
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return {-std::exp(t[0]) * *stiffness_, {}};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int, Immersion) const override {
    return {-std::exp(t[0]) * *stiffness_, {}};
  }
  EffectLocation Location(const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x0 = x0_;
    l.x1 = x1_;
    l.x = 0.5 * (l.x0 + l.x1);
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    return {{"stiffness_loss_fraction", "1", std::exp(t[0])}};
  }

 private:
  SparseMatrix own_;
  const SparseMatrix* stiffness_;
  double x0_, x1_;
};

// A member's end connections made semi-rigid: a rotational spring between each
// connected end of the member's end element and its joint, k = k_rr (1 - loss)
// / loss, k_rr the element's own rotational stiffness at that end (loss =
// exp(theta_0): the fraction of that end's rotational stiffness lost, the
// spring in series with it), condensed out statically. For an end element of
// stiffness K and mass M with the connected rotations R: A = K_RR + D (D the
// springs), G = K_R A^-1; dK = -G K_R', dM = -G M_R' - M_R G' + G M_RR G'.
class ConnectionLoss : public Base {
 public:
  ConnectionLoss(const Structure& s, EffectRegion region, const MemberConnections& c)
      : Base(s, std::move(region)), c_(c) {
    const ElementMatrices& e = s.elements[static_cast<std::size_t>(c.element)];
    x0_ = e.x0;
    x1_ = e.x1;
  }
  std::string kind() const override { return "stiffness_loss"; }
  std::vector<EffectParameter> Parameters() const override {
    return {LogQuantity(
        {"ln_loss", "ln(fraction of the end connections' rotational stiffness lost)",
         std::log(3e-3), std::log(0.9), false},
        "loss", 1.0, kMaxLoss)};
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    return {VectorOf({std::log(0.03)}), VectorOf({std::log(0.3)})};
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return Condensed(t[0], false);
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int, Immersion) const override {
    return Condensed(t[0], true);
  }
  EffectLocation Location(const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x0 = x0_;
    l.x1 = x1_;
    l.x = 0.5 * (l.x0 + l.x1);
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    const double loss = std::exp(t[0]);
    std::vector<EffectMagnitude> m = {{"stiffness_loss_fraction", "1", loss}};
    // Each connection's spring, the mean over the connected ends.
    double sum = 0;
    int count = 0;
    for (const ConnectionEnd& end : c_.ends) {
      for (int r : end.rotations) {
        sum += end.k(r, r) * (1.0 - loss) / loss;
        ++count;
      }
    }
    if (count > 0) m.push_back({"connection spring (mean)", "N m/rad", sum / count});
    return m;
  }

 private:
  // The change at theta_0 = ln(loss), or its derivative with respect to it.
  ModelChange Condensed(double theta, bool derivative) const {
    const double loss = std::exp(theta);
    std::vector<Eigen::Triplet<double>> kt, mt;
    for (const ConnectionEnd& end : c_.ends) {
      const auto nr = static_cast<Eigen::Index>(end.rotations.size());
      const auto nd = static_cast<Eigen::Index>(end.dofs.size());
      Eigen::MatrixXd k_r(nd, nr), m_r(nd, nr), m_rr(nr, nr), a(nr, nr);
      Eigen::VectorXd d_springs(nr);  // dD / dtheta
      for (Eigen::Index j = 0; j < nr; ++j) {
        const int r = end.rotations[static_cast<std::size_t>(j)];
        k_r.col(j) = end.k.col(r);
        m_r.col(j) = end.m.col(r);
        for (Eigen::Index i = 0; i < nr; ++i) {
          const int q = end.rotations[static_cast<std::size_t>(i)];
          a(i, j) = end.k(q, r);
          m_rr(i, j) = end.m(q, r);
        }
        // D_j = k_rr (1 / loss - 1): dD_j / dtheta = -k_rr / loss.
        a(j, j) += end.k(r, r) * (1.0 / loss - 1.0);
        d_springs[j] = -end.k(r, r) / loss;
      }
      const Eigen::MatrixXd a_inv = a.inverse();  // 1 x 1 or 2 x 2, positive definite
      const Eigen::MatrixXd g = k_r * a_inv;      // nd x nr
      Eigen::MatrixXd dk, dm;
      if (!derivative) {
        dk = -g * k_r.transpose();
        dm = -g * m_r.transpose() - m_r * g.transpose() + g * m_rr * g.transpose();
      } else {
        // dA = dD, dG = -G dD A^-1; d(dK) = G dD G'.
        const Eigen::MatrixXd dg = -g * d_springs.asDiagonal() * a_inv;
        dk = g * d_springs.asDiagonal() * g.transpose();
        dm = -dg * m_r.transpose() - m_r * dg.transpose() + dg * m_rr * g.transpose() +
             g * m_rr * dg.transpose();
      }
      for (Eigen::Index i = 0; i < nd; ++i) {
        for (Eigen::Index j = 0; j < nd; ++j) {
          kt.emplace_back(end.dofs[static_cast<std::size_t>(i)],
                          end.dofs[static_cast<std::size_t>(j)], dk(i, j));
          mt.emplace_back(end.dofs[static_cast<std::size_t>(i)],
                          end.dofs[static_cast<std::size_t>(j)], dm(i, j));
        }
      }
    }
    SparseMatrix k = Zero(n()), m = Zero(n());
    k.setFromTriplets(kt.begin(), kt.end());
    m.setFromTriplets(mt.begin(), mt.end());
    return {k, m};
  }

  const MemberConnections& c_;
  double x0_ = 0, x1_ = 0;
};

// A point mass m = m_ref exp(theta_0) on one node's translational DOFs and,
// where the node has rotational DOFs and rotary inertia is fitted, a rotary
// inertia m r^2 about each of its axes, r = l_ref exp(theta_1):
// dM = m (U_t + r^2 U_r).
class AttachedMass : public Base {
 public:
  AttachedMass(const Structure& s, EffectRegion region, double reference_mass,
               double position, const std::vector<int>& rotation_dofs,
               double reference_length)
      : Base(s, std::move(region)),
        m_ref_(reference_mass),
        l_ref_(reference_length),
        position_(position) {
    std::vector<Eigen::Triplet<double>> t;
    for (int d : region_.dofs) t.emplace_back(d, d, 1.0);
    unit_ = Zero(n());
    unit_.setFromTriplets(t.begin(), t.end());
    if (!rotation_dofs.empty() && l_ref_ > 0) {
      t.clear();
      for (int d : rotation_dofs) t.emplace_back(d, d, 1.0);
      rotary_ = Zero(n());
      rotary_.setFromTriplets(t.begin(), t.end());
    }
  }
  std::string kind() const override { return "attached_mass"; }
  std::vector<EffectParameter> Parameters() const override {
    std::vector<EffectParameter> p = {
        LogQuantity({"ln_mass_ratio", "ln(mass / the structure's mass)", std::log(1e-4),
                     std::log(2.0), false},
                    "mass_kg", m_ref_)};
    if (Rotary()) p.push_back(RadiusOfGyrationParameter(l_ref_));
    return p;
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    if (!Rotary()) return {VectorOf({std::log(0.003)}), VectorOf({std::log(0.1)})};
    // Small and large masses of negligible inertia, and a large one of a
    // radius a tenth of the extent (and the point mass: FitInstance, from the
    // first with the radius held at its lower bound).
    return {VectorOf({std::log(0.003), std::log(0.01)}),
            VectorOf({std::log(0.1), std::log(0.01)}),
            VectorOf({std::log(0.1), std::log(0.1)})};
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    const double m = m_ref_ * std::exp(t[0]);
    if (!Rotary()) return {{}, m * unit_};
    const double r2 = Square(l_ref_ * std::exp(t[1]));
    return {{}, m * unit_ + (m * r2) * rotary_};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i,
                         Immersion immersion) const override {
    if (i == 0) return Change(t, immersion);  // linear in m = m_ref exp(theta_0)
    const double m = m_ref_ * std::exp(t[0]);
    return {{}, (2 * m * Square(l_ref_ * std::exp(t[1]))) * rotary_};
  }
  EffectLocation Location(const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x = position_;
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    const double m = m_ref_ * std::exp(t[0]);
    std::vector<EffectMagnitude> out = {
        {"mass", "kg", m}, {"mass_ratio", "1 (of the structure's mass)", std::exp(t[0])}};
    if (Rotary()) {
      const double r = l_ref_ * std::exp(t[1]);
      out.push_back({"radius_of_gyration", "m", r});
      out.push_back({"rotary_inertia", "kg m^2", m * r * r});
    }
    return out;
  }

 private:
  static double Square(double v) { return v * v; }
  bool Rotary() const { return rotary_.size() > 0; }
  double m_ref_;
  double l_ref_;
  double position_;
  SparseMatrix unit_;
  SparseMatrix rotary_;  // 0 x 0: no rotary inertia fitted
};

// A point mass between the end nodes of a line element, at a fraction xi of
// its length (fitted): dM = m sum_d w_d(xi) w_d(xi)', w_d the weights that
// read the element's translation along each axis the model has DOFs for
// (femup/sensor.h: cubic Hermite across, linear along), so the mass moves with
// the element's displacement field where it sits; dM/dxi from the weights'
// slopes. xi stays 0.05 from the ends, where the node instances act. A line
// of several segments end to end (Structure::attached_mass_lines: a refined
// mesh's elements along one of the model's) is one candidate: xi is the
// fraction of the whole line, and the mass sits on the segment it falls in.
// With rotary inertia, + m r^2 sum_a v_a(xi) v_a(xi)', v_a the weights that
// read the element's rotation about each of the model's rotation axes.
class SegmentMass : public Base {
 public:
  // `rotation_axes`: the axes the model has rotational DOFs about where rotary
  // inertia is fitted (a third parameter, ln(r / l_ref)); empty: none.
  SegmentMass(const Structure& s, EffectRegion region, double reference_mass,
              std::vector<LineSegment> line, std::vector<Eigen::Vector3d> axes,
              double position_a, double position_b,
              std::vector<Eigen::Vector3d> rotation_axes, double reference_length)
      : Base(s, std::move(region)),
        m_ref_(reference_mass),
        l_ref_(reference_length),
        line_(std::move(line)),
        axes_(std::move(axes)),
        rotation_axes_(l_ref_ > 0 ? std::move(rotation_axes)
                                  : std::vector<Eigen::Vector3d>()),
        position_a_(position_a),
        position_b_(position_b) {
    ends_.push_back(0.0);
    std::vector<std::string> nodes;
    for (const LineSegment& g : line_) {
      ends_.push_back(ends_.back() + (g.b - g.a).norm());
      for (int node : {g.node_a, g.node_b})
        if (node >= 0) nodes.push_back(s_.nodes[static_cast<std::size_t>(node)].name);
    }
    dofs_ = IndexDofLabels(s_, nodes);
  }
  std::string kind() const override { return "attached_mass"; }
  std::vector<EffectParameter> Parameters() const override {
    std::vector<EffectParameter> p = {
        LogQuantity({"ln_mass_ratio", "ln(mass / the structure's mass)", std::log(1e-4),
                     std::log(2.0), false},
                    "mass_kg", m_ref_),
        {"xi", "position along the element from its first node (fraction)", 0.05, 0.95,
         false}};
    if (Rotary()) p.push_back(RadiusOfGyrationParameter(l_ref_));
    return p;
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    if (!Rotary())
      return {VectorOf({std::log(0.003), 0.3}), VectorOf({std::log(0.1), 0.7})};
    return {VectorOf({std::log(0.003), 0.3, std::log(0.01)}),
            VectorOf({std::log(0.1), 0.7, std::log(0.01)}),
            VectorOf({std::log(0.1), 0.5, std::log(0.1)})};
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    const double m = m_ref_ * std::exp(t[0]);
    if (!Rotary()) return {{}, Outer(t[1], false, false) * m};
    return {{}, Outer(t[1], false, false) * m + Outer(t[1], false, true) * (m * R2(t))};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i,
                         Immersion immersion) const override {
    if (i == 0) return Change(t, immersion);  // linear in m = m_ref exp(theta_0)
    const double m = m_ref_ * std::exp(t[0]);
    if (i == 2) return {{}, Outer(t[1], false, true) * (2 * m * R2(t))};
    if (!Rotary()) return {{}, Outer(t[1], true, false) * m};
    return {{}, Outer(t[1], true, false) * m + Outer(t[1], true, true) * (m * R2(t))};
  }
  EffectLocation Location(const Eigen::VectorXd& t) const override {
    EffectLocation l;
    l.x = (1 - t[1]) * position_a_ + t[1] * position_b_;
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    const double m = m_ref_ * std::exp(t[0]);
    std::vector<EffectMagnitude> out = {
        {"mass", "kg", m},
        {"mass_ratio", "1 (of the structure's mass)", std::exp(t[0])},
        {"distance_from_first_node", "m", t[1] * ends_.back()}};
    if (Rotary()) {
      out.push_back({"radius_of_gyration", "m", std::sqrt(R2(t))});
      out.push_back({"rotary_inertia", "kg m^2", m * R2(t)});
    }
    return out;
  }

 private:
  bool Rotary() const { return !rotation_axes_.empty(); }
  double R2(const Eigen::VectorXd& t) const {
    const double r = l_ref_ * std::exp(t[2]);
    return r * r;
  }
  // sum_d w_d w_d', or with `slope` its derivative sum_d (w_d' w_d + w_d w_d'),
  // on the segment xi falls in (its own fraction: d local / d xi = the line's
  // length over the segment's); w_d reads the translation along each of the
  // model's axes, or with `rotation` the rotation about each rotation axis.
  SparseMatrix Outer(double xi, bool slope, bool rotation) const {
    const double at = xi * ends_.back();
    std::size_t k = 0;
    while (k + 1 < line_.size() && at > ends_[k + 1]) ++k;
    const double length = ends_[k + 1] - ends_[k];
    const double local = std::clamp((at - ends_[k]) / length, 0.0, 1.0);
    const double stretch = ends_.back() / length;
    std::vector<Eigen::Triplet<double>> t;
    for (const Eigen::Vector3d& d : rotation ? rotation_axes_ : axes_) {
      const auto w = SegmentWeights(s_, dofs_, line_[k], local, d, rotation);
      const auto dw =
          slope ? SegmentWeights(s_, dofs_, line_[k], local, d, rotation, true) : w;
      for (const auto& [i, wi] : dw) {
        for (const auto& [j, wj] : w) {
          const double v = slope ? stretch * wi * wj : wi * wj;
          t.emplace_back(i, j, v);
          if (slope) t.emplace_back(j, i, v);
        }
      }
    }
    SparseMatrix m = Zero(n());
    m.setFromTriplets(t.begin(), t.end());
    return m;
  }
  double m_ref_;
  double l_ref_;
  std::vector<LineSegment> line_;
  std::vector<double> ends_;  // distance from the line's start to each segment's ends
  DofLabelIndex dofs_;        // the line's nodes' DOFs
  std::vector<Eigen::Vector3d> axes_;
  std::vector<Eigen::Vector3d> rotation_axes_;
  double position_a_, position_b_;
};

// The added-mass bases times ratio = exp(theta_0): on the flagged wet elements
// (no level), or below a level theta_1 (m) where the elements have heights.
class AddedMass : public Base {
 public:
  AddedMass(const Structure& s, EffectRegion region, bool with_level, bool wet_only)
      : Base(s, std::move(region)), with_level_(with_level), wet_only_(wet_only) {
    flagged_ = Zero(n());
    if (!with_level_) {
      for (int e : region_.elements) flagged_ += s_.elements[e].added_mass_basis;
    }
  }
  std::string kind() const override { return "added_mass"; }
  std::vector<EffectParameter> Parameters() const override {
    std::vector<EffectParameter> p = {
        LogQuantity({"ln_mass_ratio", "ln(added mass / the elements' added-mass basis)",
                     std::log(1e-3), std::log(5.0), false},
                    "ratio", 1.0)};
    if (with_level_) {
      p.push_back(
          LinearQuantity({"level", "height of the water level above the support (m)",
                          Bottom() + 0.05 * (Top() - Bottom()), Top(), true},
                         "level_m", 1.0, Bottom(), Top()));
    }
    return p;
  }
  std::vector<Eigen::VectorXd> Starts() const override {
    if (!with_level_) return {VectorOf({std::log(0.05)}), VectorOf({std::log(0.5)})};
    std::vector<Eigen::VectorXd> out;
    for (double f : {0.3, 0.6, 0.95})
      out.push_back(VectorOf({std::log(0.05), Bottom() + f * (Top() - Bottom())}));
    return out;
  }
  ModelChange Change(const Eigen::VectorXd& t, Immersion immersion) const override {
    if (wet_only_ && immersion != Immersion::kWet) return {};
    return {{}, std::exp(t[0]) * Basis(t)};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i,
                         Immersion immersion) const override {
    if (wet_only_ && immersion != Immersion::kWet) return {};
    if (i == 0) return {{}, std::exp(t[0]) * Basis(t)};
    // d/d level: the element the level cuts gains basis / height. At a node
    // the basis has a kink: there the mean of the two sides (what central
    // differences give), never zero, or a fit started at a node (every start
    // is one on a uniform mesh) would never move the level.
    SparseMatrix d = Zero(n());
    for (int e : region_.elements) {
      const ElementMatrices& el = s_.elements[e];
      const double h = el.x1 - el.x0, tol = 1e-9 * h;
      if (t[1] > el.x0 + tol && t[1] < el.x1 - tol) {
        d += el.added_mass_basis / h;
      } else if (std::abs(t[1] - el.x0) <= tol || std::abs(t[1] - el.x1) <= tol) {
        d += 0.5 * el.added_mass_basis / h;
      }
    }
    return {{}, std::exp(t[0]) * d};
  }
  EffectLocation Location(const Eigen::VectorXd& t) const override {
    EffectLocation l;
    l.x0 = Bottom();
    l.x1 = with_level_ ? t[1] : s_.elements[region_.elements.back()].x1;
    if (with_level_) l.depth = t[1];
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    std::vector<EffectMagnitude> m = {
        {"added_mass_ratio", "1 (of the added-mass basis)", std::exp(t[0])}};
    if (with_level_) m.push_back({"water_level", "m", t[1]});
    return m;
  }

 private:
  double Bottom() const { return s_.elements[region_.elements.front()].x0; }
  double Top() const { return s_.elements[region_.elements.back()].x1; }
  SparseMatrix Basis(const Eigen::VectorXd& t) const {
    if (!with_level_) return flagged_;
    SparseMatrix b = Zero(n());
    for (int e : region_.elements) {
      const ElementMatrices& el = s_.elements[e];
      const double w = std::clamp((t[1] - el.x0) / (el.x1 - el.x0), 0.0, 1.0);
      if (w > 0) b += w * el.added_mass_basis;
    }
    return b;
  }
  bool with_level_;
  bool wet_only_;
  SparseMatrix flagged_;
};

// What both forms of support_flexibility share: a compliance ratio c =
// exp(theta) in [1e-3, 100] (what it is relative to and, where a builder
// states another range, that range: each form says) on every
// restrained direction, one for the translations and one for the rotations
// where the supports restrain both (a footing gives sideways and in rocking by
// different amounts: a soil's horizontal and rocking stiffness are not one
// number), else one for all; starts at a fifth and three fifths of the range
// in ln c (0.01 and 1 of the default), and a location at
// the structure's first element.
class SupportFamily : public Base {
 public:
  // `rotations[i]`: whether the i-th restrained direction (each form says
  // which it counts) is a rotation.
  SupportFamily(const Structure& s, EffectRegion region,
                const std::vector<bool>& rotations)
      : Base(s, std::move(region)) {
    const bool any_rotation =
        std::find(rotations.begin(), rotations.end(), true) != rotations.end();
    const bool any_translation =
        std::find(rotations.begin(), rotations.end(), false) != rotations.end();
    split_ = any_rotation && any_translation;
    for (const bool rotation : rotations) acts_.push_back(ParameterOf(rotation));
  }
  std::string kind() const override { return "support_flexibility"; }
  std::vector<EffectParameter> Parameters() const override {
    const auto [lo, hi] = Range();
    if (!split_) {
      return {LogQuantity(
          {"ln_compliance_ratio", Meaning(""), std::log(lo), std::log(hi), false},
          "compliance_ratio", 1.0)};
    }
    return {LogQuantity({"ln_translation_compliance_ratio", Meaning("translation "),
                         std::log(lo), std::log(hi), false},
                        "translation_compliance_ratio", 1.0),
            LogQuantity({"ln_rotation_compliance_ratio", Meaning("rotation "),
                         std::log(lo), std::log(hi), false},
                        "rotation_compliance_ratio", 1.0)};
  }
  // At a fifth and three fifths of the range in ln c (0.01 and 1 of the
  // default range).
  std::vector<Eigen::VectorXd> Starts() const override {
    const auto [lo, hi] = Range();
    const double stiff = std::log(lo) + 0.2 * std::log(hi / lo),
                 soft = std::log(lo) + 0.6 * std::log(hi / lo);
    if (!split_) return {VectorOf({stiff}), VectorOf({soft})};
    return {VectorOf({stiff, stiff}), VectorOf({soft, soft}), VectorOf({stiff, soft}),
            VectorOf({soft, stiff})};
  }
  EffectLocation Location(const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x = s_.elements.empty() ? 0.0 : s_.elements.front().x0;
    return l;
  }

 protected:
  // What a compliance ratio is relative to ("ln(added compliance / ...)").
  virtual std::string Meaning(const std::string& which) const = 0;
  // The range of the compliance ratios.
  virtual std::pair<double, double> Range() const { return {1e-3, 100.0}; }
  // The parameter that acts on a direction.
  int ParameterOf(bool rotation) const { return split_ && rotation ? 1 : 0; }
  // The compliance ratio on a direction.
  double Compliance(const Eigen::VectorXd& t, bool rotation) const {
    return std::exp(t[ParameterOf(rotation)]);
  }
  // The parameter that acts on the i-th restrained direction, and its ratio
  // there (worked out once, in the constructor: Change and Derivative are
  // evaluated at every step of every fit).
  int ActingOn(std::size_t i) const { return acts_[i]; }
  double ComplianceAt(const Eigen::VectorXd& t, std::size_t i) const {
    return std::exp(t[acts_[i]]);
  }
  std::vector<EffectMagnitude> Ratios(const Eigen::VectorXd& t) const {
    if (!split_) return {{"compliance_ratio", "1", std::exp(t[0])}};
    return {{"translation_compliance_ratio", "1", std::exp(t[0])},
            {"rotation_compliance_ratio", "1", std::exp(t[1])}};
  }

 private:
  bool split_ = false;
  std::vector<int> acts_;  // per restrained direction: its parameter
};

bool IsRotationDof(const Structure& s, int dof) {
  return IsRotation(internal::SplitDofLabel(s.dof_labels[dof]).second);
}

std::vector<bool> SpringRotations(const Structure& s) {
  std::vector<bool> out;
  for (const SupportSpring& sp : s.supports) out.push_back(IsRotationDof(s, sp.dof));
  return out;
}

std::vector<bool> RigidRotations(const Structure& s) {
  std::vector<bool> out;
  for (const RigidSupport& sp : s.rigid_supports)
    for (const std::string& d : sp.directions) out.push_back(IsRotation(d));
  return out;
}

// Each support spring k in series with one c times more compliant (c its
// direction's ratio): k -> k / (1 + c), dK = -k c / (1 + c) on its DOF.
class SupportFlexibility : public SupportFamily {
 public:
  SupportFlexibility(const Structure& s, EffectRegion region)
      : SupportFamily(s, std::move(region), SpringRotations(s)) {}
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return {Springs(t, -1, [](double c) { return -c / (1 + c); }), {}};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i, Immersion) const override {
    // d/dtheta of -c/(1+c), on the springs parameter i acts on.
    return {Springs(t, i, [](double c) { return -c / ((1 + c) * (1 + c)); }), {}};
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    std::vector<EffectMagnitude> m = Ratios(t);
    for (std::size_t i = 0; i < s_.supports.size(); ++i) {
      const SupportSpring& sp = s_.supports[i];
      m.push_back(
          {sp.name + " stiffness", sp.unit, sp.stiffness / (1 + ComplianceAt(t, i))});
    }
    return m;
  }

 protected:
  std::string Meaning(const std::string& which) const override {
    return "ln(added " + which + "compliance / the support's own)";
  }

 private:
  // diag(factor(c) k) on the springs' DOFs (only those parameter `only` acts
  // on, where it is >= 0).
  template <typename Factor>
  SparseMatrix Springs(const Eigen::VectorXd& t, int only, Factor factor) const {
    std::vector<Eigen::Triplet<double>> tr;
    for (std::size_t i = 0; i < s_.supports.size(); ++i) {
      const SupportSpring& sp = s_.supports[i];
      if (only >= 0 && ActingOn(i) != only) continue;
      tr.emplace_back(sp.dof, sp.dof, factor(ComplianceAt(t, i)) * sp.stiffness);
    }
    SparseMatrix k = Zero(n());
    k.setFromTriplets(tr.begin(), tr.end());
    return k;
  }
};

// Where the supports are rigid (Structure::rigid_supports): a spring on each
// restrained direction d of every support, k_d = k_bb(d, d) / c_d with c_d =
// its direction's compliance ratio (k_bb(d, d): the stiffness the elements
// meeting there give that direction, so c = 1 is a spring as stiff as the
// members' ends), condensed out statically (Guyan): with A = (k_bb + D)^-1, D
// = diag(k_bb(d, d) / c_d), and T = -A k_fb', dK = k_fb T and dM = m_fb T +
// T' m_fb' + T' m_bb T on the rows the support couples to. c -> 0 is the rigid
// support (dK, dM -> 0); c -> inf frees the restrained directions.
class RigidSupportFlexibility : public SupportFamily {
 public:
  RigidSupportFlexibility(const Structure& s, EffectRegion region)
      : SupportFamily(s, std::move(region), RigidRotations(s)) {}
  ModelChange Change(const Eigen::VectorXd& t, Immersion) const override {
    return Condensed(t, -1);
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i, Immersion) const override {
    return Condensed(t, i);
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    std::vector<EffectMagnitude> m = Ratios(t);
    // Each direction's spring, the mean over the supports.
    const RigidSupport& first = s_.rigid_supports.front();
    for (std::size_t d = 0; d < first.directions.size(); ++d) {
      const std::string& dir = first.directions[d];
      const bool rotation = IsRotation(dir);
      double sum = 0;
      for (const RigidSupport& sp : s_.rigid_supports)
        sum += Reference(sp, static_cast<Eigen::Index>(d)) / Compliance(t, rotation);
      m.push_back({"base spring " + dir + " (mean of " +
                       std::to_string(s_.rigid_supports.size()) + " supports)",
                   rotation ? "N m/rad" : "N/m",
                   sum / static_cast<double>(s_.rigid_supports.size())});
    }
    return m;
  }

 protected:
  std::string Meaning(const std::string& which) const override {
    return "ln(a base spring's " + which +
           "compliance / the members' own end compliance)";
  }

  // The builder's range where it states one (its first support's).
  std::pair<double, double> Range() const override {
    const RigidSupport& first = s_.rigid_supports.front();
    if (first.min_compliance > 0 && first.max_compliance > first.min_compliance)
      return {first.min_compliance, first.max_compliance};
    return SupportFamily::Range();
  }

 private:
  // The stiffness direction j's compliance ratio is relative to.
  static double Reference(const RigidSupport& sp, Eigen::Index j) {
    return sp.reference.size() > 0 ? sp.reference[j] : sp.k_bb(j, j);
  }
  // The change at theta (`derivative` < 0), or its derivative with respect to
  // parameter `derivative` (a ln c).
  ModelChange Condensed(const Eigen::VectorXd& t, int derivative) const {
    std::vector<Eigen::Triplet<double>> kt, mt;
    std::size_t first = 0;  // the support's first direction, of all supports'
    for (const RigidSupport& sp : s_.rigid_supports) {
      const Eigen::Index nd = sp.k_bb.rows();
      first += sp.directions.size();
      if (sp.rows.empty()) continue;
      const std::size_t at = first - sp.directions.size();
      Eigen::VectorXd springs(nd),
          acted(nd);  // D's diagonal; its part under `derivative`
      for (Eigen::Index j = 0; j < nd; ++j) {
        const std::size_t i = at + static_cast<std::size_t>(j);
        springs[j] = Reference(sp, j) / ComplianceAt(t, i);
        acted[j] = ActingOn(i) == derivative ? springs[j] : 0.0;
      }
      const Eigen::MatrixXd kb = sp.k_bb + Eigen::MatrixXd(springs.asDiagonal());
      const Eigen::MatrixXd a = kb.ldlt().solve(Eigen::MatrixXd::Identity(nd, nd));
      const Eigen::MatrixXd tr = -a * sp.k_fb.transpose();  // T: directions x rows
      Eigen::MatrixXd dk, dm;
      if (derivative < 0) {
        dk = sp.k_fb * tr;
        dm = sp.m_fb * tr + tr.transpose() * sp.m_fb.transpose() +
             tr.transpose() * sp.m_bb * tr;
      } else {
        // dD/dln c = -D_c (D's part under c), dA = A D_c A, so dT = -dA k_fb'
        // = A D_c T.
        const Eigen::MatrixXd dt = a * acted.asDiagonal() * tr;
        dk = sp.k_fb * dt;
        dm = sp.m_fb * dt + dt.transpose() * sp.m_fb.transpose() +
             dt.transpose() * sp.m_bb * tr + tr.transpose() * sp.m_bb * dt;
      }
      const int r = static_cast<int>(sp.rows.size());
      for (int i = 0; i < r; ++i) {
        for (int j = 0; j < r; ++j) {
          kt.emplace_back(sp.rows[i], sp.rows[j], dk(i, j));
          mt.emplace_back(sp.rows[i], sp.rows[j], dm(i, j));
        }
      }
    }
    SparseMatrix k = Zero(n()), m = Zero(n());
    k.setFromTriplets(kt.begin(), kt.end());
    m.setFromTriplets(mt.begin(), mt.end());
    return {k, m};
  }
};

}  // namespace

std::vector<std::string> ModelEffectKinds() {
  return {"added_mass",     "support_flexibility", "attached_mass",
          "stiffness_loss", "material_scaling",    "axial_load"};
}

double ReferenceLength(const Structure& structure) {
  if (structure.nodes.empty()) return 0.0;
  Eigen::Vector3d lo = structure.nodes.front().xyz, hi = lo;
  for (const ModelNode& node : structure.nodes) {
    lo = lo.cwiseMin(node.xyz);
    hi = hi.cwiseMax(node.xyz);
  }
  for (const LineSegment& g : structure.segments) {  // supports beyond the nodes
    lo = lo.cwiseMin(g.a).cwiseMin(g.b);
    hi = hi.cwiseMax(g.a).cwiseMax(g.b);
  }
  return (hi - lo).maxCoeff();
}

double ReferenceMass(const Structure& s) {
  std::map<std::string, Eigen::VectorXd> rigid;  // component -> unit translation
  const int n = static_cast<int>(s.dof_labels.size());
  for (int i = 0; i < n; ++i) {
    const auto [node, component] = internal::SplitDofLabel(s.dof_labels[i]);
    if (!IsTranslation(component)) continue;
    auto it = rigid.try_emplace(component, Eigen::VectorXd::Zero(n)).first;
    it->second[i] = 1.0;
  }
  double best = 0;
  for (const auto& [component, u] : rigid) best = std::max(best, u.dot(s.mass * u));
  return best;
}

std::vector<FamilyApplicability> ApplicableModelEffects(const Structure& s) {
  const bool elements = HasElementMatrices(s);
  const std::string no_elements =
      "the model has no element matrices (a Matrix Market model needs `elements`)";
  std::vector<FamilyApplicability> out;
  for (const std::string& kind : ModelEffectKinds()) {
    std::string why;
    if (kind == "material_scaling" || kind == "stiffness_loss") {
      if (!elements) why = no_elements;
    } else if (kind == "added_mass") {
      const bool any_wet = std::any_of(s.elements.begin(), s.elements.end(),
                                       [](const ElementMatrices& e) { return e.wet; });
      if (!elements) {
        why = no_elements;
      } else if (!HasHeights(s) && !any_wet) {
        why = "no element is wet and the elements have no heights for a water level";
      }
    } else if (kind == "support_flexibility") {
      if (s.supports.empty() && s.rigid_supports.empty()) {
        why =
            "the model's supports are rigid (their DOFs are not in the model) and its "
            "builder does not know the elements that meet them; give them as springs to "
            "diagnose their flexibility";
      }
    } else if (kind == "attached_mass") {
      if (!(ReferenceMass(s) > 0)) why = "the model has no translational DOF with mass";
    } else if (kind == "axial_load") {
      if (!elements || !HasHeights(s))
        why =
            "its elements have no geometric stiffness for an axial force (a cantilever's "
            "do)";
    }
    out.push_back({kind, why, kind != "axial_load"});
  }
  return out;
}

std::string MemberPartName(const ElementMember& member, const MemberPart& part) {
  char span[32];
  std::snprintf(span, sizeof span, " (%.2f-%.2f)", part.from, part.to);
  return "member " + member.label + span;
}

std::vector<std::unique_ptr<ModelEffect>> CreateModelEffects(
    const std::string& kind, const Structure& s, const ModelEffectOptions& options) {
  const std::vector<std::string> kinds = ModelEffectKinds();
  if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
    std::string list;
    for (const auto& k : kinds) list += (list.empty() ? "" : ", ") + k;
    throw InputError("effect", "unknown kind '" + kind + "' (known: " + list + ")");
  }
  for (const FamilyApplicability& a : ApplicableModelEffects(s)) {
    if (a.kind == kind && !a.why_not.empty()) {
      throw InputError("effect", kind + " does not apply to this " +
                                     (s.type.empty() ? std::string("model") : s.type) +
                                     " model: " + a.why_not);
    }
  }
  std::vector<std::unique_ptr<ModelEffect>> out;
  const int num_elements = static_cast<int>(s.elements.size());
  if (kind == "material_scaling") {
    EffectRegion r{"all elements", {}, {}};
    for (int e = 0; e < num_elements; ++e) r.elements.push_back(e);
    out.push_back(std::make_unique<MaterialScaling>(s, std::move(r)));
  } else if (kind == "stiffness_loss") {
    for (int e = 0; e < num_elements; ++e) {
      out.push_back(std::make_unique<StiffnessLoss>(
          s, EffectRegion{"element " + s.elements[e].label, {e}, {}}, s.elements[e]));
    }
    // A member's end connections, where the builder knows them (a plane
    // frame's beams): semi-rigid rather than rigid.
    for (const MemberConnections& c : s.connections) {
      out.push_back(std::make_unique<ConnectionLoss>(
          s, EffectRegion{"connections of " + c.label, {c.element}, {}}, c));
    }
    // And each member of a group on its own, up to the stated number.
    const int num_members = static_cast<int>(s.members.size());
    if (options.max_members < 0 || num_members <= options.max_members) {
      // How many members each element holds: a member that is its element's
      // only one (a plane frame's) is that element's instance already.
      std::map<int, int> per_element;
      for (const ElementMember& m : s.members) ++per_element[m.element];
      for (const ElementMember& m : s.members) {
        const int index = static_cast<int>(&m - s.members.data());
        EffectRegion r{"member " + m.label, {}, {}, index};
        if (m.element >= 0) r.elements.push_back(m.element);
        if (m.element < 0 || per_element[m.element] > 1)
          out.push_back(std::make_unique<StiffnessLoss>(s, r, m));
        // And each of its finite elements: a loss over part of its length.
        for (const MemberPart& part : m.parts) {
          EffectRegion pr = r;
          pr.name = MemberPartName(m, part);
          pr.part = static_cast<int>(&part - m.parts.data());
          ElementMember piece{m.label, m.element, part.stiffness, part.x0, part.x1, {}};
          out.push_back(std::make_unique<StiffnessLoss>(s, std::move(pr), piece));
        }
      }
    }
  } else if (kind == "attached_mass") {
    // One instance per node with translational DOFs, in DOF order (only the
    // structure's attached_mass_nodes where it names them).
    const double m_ref = ReferenceMass(s);
    // Rotary inertia where the model has rotations and node coordinates.
    const double l_ref = options.rotary_inertia ? ReferenceLength(s) : 0.0;
    std::vector<std::string> order;
    std::map<std::string, std::vector<int>> dofs, rotations;
    std::map<std::string, double> position;
    for (int i = 0; i < static_cast<int>(s.dof_labels.size()); ++i) {
      const auto [node, component] = internal::SplitDofLabel(s.dof_labels[i]);
      if (IsRotation(component)) rotations[node].push_back(i);
      if (!IsTranslation(component)) continue;
      if (!dofs.count(node)) {
        order.push_back(node);
        position[node] = i < static_cast<int>(s.dof_positions.size())
                             ? s.dof_positions[i]
                             : static_cast<double>(order.size());
      }
      dofs[node].push_back(i);
    }
    for (const std::string& node : order) {
      const auto& only = s.attached_mass_nodes;
      if (!only.empty() && std::find(only.begin(), only.end(), node) == only.end())
        continue;
      out.push_back(
          std::make_unique<AttachedMass>(s, EffectRegion{"node " + node, {}, dofs[node]},
                                         m_ref, position[node], rotations[node], l_ref));
    }
    // Between the nodes, where the model has line elements: one instance per
    // element segment (only the structure's attached_mass_segments where it
    // names its few candidate nodes), its position fitted. The region is the member it
    // belongs to, so a stated region that names a member keeps its segments and one that
    // names a node its node.
    const std::vector<Eigen::Vector3d> axes = AxesWithDofs(s, 'u');
    const std::vector<Eigen::Vector3d> rotation_axes =
        l_ref > 0 ? AxesWithDofs(s, 'r') : std::vector<Eigen::Vector3d>();
    std::vector<std::vector<LineSegment>> between;
    if (!s.attached_mass_lines.empty()) {
      for (const std::vector<int>& line : s.attached_mass_lines) {
        between.emplace_back();
        for (int i : line) between.back().push_back(s.segments.at(i));
      }
    } else if (!s.attached_mass_nodes.empty()) {
      for (int i : s.attached_mass_segments) between.push_back({s.segments.at(i)});
    } else {
      for (const LineSegment& g : s.segments) between.push_back({g});
    }
    for (std::vector<LineSegment>& line : between) {
      if (line.empty()) continue;
      const int node_a = line.front().node_a, node_b = line.back().node_b;
      if (node_a < 0 && node_b < 0) continue;
      const std::string a = node_a >= 0 ? s.nodes[node_a].name : "the support";
      const std::string b = node_b >= 0 ? s.nodes[node_b].name : "the support";
      EffectRegion r{a + "-" + b, {}, {}};
      if (line.front().element >= 0) r.elements.push_back(line.front().element);
      const auto at = [&](const std::string& node) {
        return position.count(node) ? position[node] : 0.0;
      };
      out.push_back(std::make_unique<SegmentMass>(
          s, std::move(r), m_ref, std::move(line), axes, node_a >= 0 ? at(a) : 0.0,
          node_b >= 0 ? at(b) : 0.0, rotation_axes, l_ref));
    }
  } else if (kind == "added_mass") {
    const bool level = HasHeights(s);
    EffectRegion r{level ? "below the water level" : "wet elements", {}, {}};
    for (int e = 0; e < num_elements; ++e) {
      if (level || s.elements[e].wet) r.elements.push_back(e);
    }
    out.push_back(
        std::make_unique<AddedMass>(s, std::move(r), level, options.wet_only_added_mass));
  } else if (kind == "axial_load") {
    EffectRegion r{"whole length", {}, {}};
    for (int e = 0; e < num_elements; ++e) r.elements.push_back(e);
    out.push_back(std::make_unique<AxialLoad>(s, std::move(r)));
  } else if (kind == "support_flexibility") {
    EffectRegion r{"supports", {}, {}};
    if (!s.supports.empty()) {
      for (const SupportSpring& sp : s.supports) r.dofs.push_back(sp.dof);
      out.push_back(std::make_unique<SupportFlexibility>(s, std::move(r)));
    } else {
      out.push_back(std::make_unique<RigidSupportFlexibility>(s, std::move(r)));
    }
  }
  return out;
}

void ApplyModelEffects(const Structure& structure,
                       const std::vector<const ModelEffect*>& effects,
                       const std::vector<Eigen::VectorXd>& thetas, Immersion immersion,
                       SparseMatrix* stiffness, SparseMatrix* mass) {
  if (effects.size() != thetas.size()) {
    throw InputError("effects", std::to_string(effects.size()) + " effects but " +
                                    std::to_string(thetas.size()) + " parameter vectors");
  }
  *stiffness = structure.stiffness;
  *mass = structure.mass;
  for (std::size_t k = 0; k < effects.size(); ++k) {
    const ModelChange c = effects[k]->Change(thetas[k], immersion);
    if (c.stiffness.size() > 0) *stiffness += c.stiffness;
    if (c.mass.size() > 0) *mass += c.mass;
  }
}

}  // namespace femup
