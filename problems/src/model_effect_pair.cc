#include "femup/problems/model_effect_pair.h"

#include <algorithm>
#include <string>
#include <utility>

#include "femup/core/errors.h"

namespace femup {
namespace {

// a + b, where an empty matrix (a change that leaves this matrix alone) is 0.
SparseMatrix Sum(SparseMatrix a, const SparseMatrix& b) {
  if (b.size() == 0) return a;
  if (a.size() == 0) return b;
  a += b;
  return a;
}

std::vector<int> Union(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

Eigen::VectorXd Joined(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd v(a.size() + b.size());
  v << a, b;
  return v;
}

class ModelEffectPair : public ModelEffect {
 public:
  ModelEffectPair(std::shared_ptr<const ModelEffect> first,
                  std::shared_ptr<const ModelEffect> second,
                  std::vector<Eigen::VectorXd> starts)
      : first_(std::move(first)), second_(std::move(second)) {
    n1_ = static_cast<int>(first_->Parameters().size());
    n2_ = static_cast<int>(second_->Parameters().size());
    region_.name = first_->region().name + " + " + second_->region().name;
    region_.elements = Union(first_->region().elements, second_->region().elements);
    region_.dofs = Union(first_->region().dofs, second_->region().dofs);
    for (std::size_t k = 0; k < starts.size(); ++k) {
      if (starts[k].size() != n1_ + n2_) {
        throw InputError("pair", "start " + std::to_string(k) + " has " +
                                     std::to_string(starts[k].size()) +
                                     " entries; the pair has " +
                                     std::to_string(n1_ + n2_) + " parameters");
      }
    }
    starts_ = std::move(starts);
    const std::vector<Eigen::VectorXd> s1 = first_->Starts(), s2 = second_->Starts();
    if (!s1.empty() && !s2.empty()) {
      for (const Eigen::VectorXd& a : s1) starts_.push_back(Joined(a, s2.front()));
      for (std::size_t k = 1; k < s2.size(); ++k)
        starts_.push_back(Joined(s1.front(), s2[k]));
    }
  }

  std::string kind() const override { return first_->kind() + "+" + second_->kind(); }
  const EffectRegion& region() const override { return region_; }
  std::vector<EffectParameter> Parameters() const override {
    std::vector<EffectParameter> p = first_->Parameters();
    for (EffectParameter& q : second_->Parameters()) p.push_back(std::move(q));
    return p;
  }
  std::vector<Eigen::VectorXd> Starts() const override { return starts_; }
  ModelChange Change(const Eigen::VectorXd& t, Immersion immersion) const override {
    ModelChange a = first_->Change(t.head(n1_), immersion);
    const ModelChange b = second_->Change(t.tail(n2_), immersion);
    return {Sum(std::move(a.stiffness), b.stiffness), Sum(std::move(a.mass), b.mass)};
  }
  ModelChange Derivative(const Eigen::VectorXd& t, int i,
                         Immersion immersion) const override {
    if (i < n1_) return first_->Derivative(t.head(n1_), i, immersion);
    return second_->Derivative(t.tail(n2_), i - n1_, immersion);
  }
  EffectLocation Location(const Eigen::VectorXd& t) const override {
    return first_->Location(t.head(n1_));
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& t) const override {
    std::vector<EffectMagnitude> m = first_->Magnitudes(t.head(n1_));
    for (EffectMagnitude& q : second_->Magnitudes(t.tail(n2_))) m.push_back(std::move(q));
    return m;
  }

 private:
  std::shared_ptr<const ModelEffect> first_, second_;
  int n1_ = 0, n2_ = 0;
  EffectRegion region_;
  std::vector<Eigen::VectorXd> starts_;
};

bool Shares(const std::vector<int>& a, const std::vector<int>& b) {
  return std::any_of(a.begin(), a.end(),
                     [&](int i) { return std::find(b.begin(), b.end(), i) != b.end(); });
}

}  // namespace

bool RegionsOverlap(const EffectRegion& a, const EffectRegion& b) {
  return Shares(a.elements, b.elements) || Shares(a.dofs, b.dofs);
}

std::unique_ptr<ModelEffect> PairOfModelEffects(std::shared_ptr<const ModelEffect> first,
                                                std::shared_ptr<const ModelEffect> second,
                                                std::vector<Eigen::VectorXd> starts) {
  if (!first || !second) throw InputError("pair", "both effects are needed");
  if (first->kind() == second->kind() &&
      RegionsOverlap(first->region(), second->region())) {
    throw InputError("pair", "both effects are " + first->kind() +
                                 " and their regions (" + first->region().name + ", " +
                                 second->region().name +
                                 ") share an element or a DOF; two places of one family "
                                 "must lie apart");
  }
  return std::make_unique<ModelEffectPair>(std::move(first), std::move(second),
                                           std::move(starts));
}

}  // namespace femup
