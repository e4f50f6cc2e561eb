#include "femup/problems/effect_priors.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {

namespace {

std::string Num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// The values a parameter's quantity can take, as an interval: "(0, 0.99]".
std::string Domain(const EffectParameter& p) {
  const double min = p.log_coordinate ? 0.0 : p.quantity_min;
  std::string out = p.log_coordinate || !std::isfinite(min) ? "(" : "[";
  out += std::isfinite(min) ? Num(min) : "-inf";
  out += ", ";
  out += std::isfinite(p.quantity_max) ? Num(p.quantity_max) + "]" : "inf)";
  return out;
}

bool InDomain(const EffectParameter& p, double q) {
  const bool above = p.log_coordinate ? q > 0 : q >= p.quantity_min;
  return above && q <= p.quantity_max;
}

// The node a DOF label belongs to: "n7" of "n7:ux"; a chain's "x3" itself.
std::string NodeOf(const std::string& label) { return label.substr(0, label.find(':')); }

bool NamesElement(const ElementMatrices& e, const std::string& name) {
  return name == std::to_string(e.id) || name == e.label;
}

// Each start clipped into the stated ranges, then one with the stated
// coordinates at their ranges' middle (a normal prior: its mean), without
// repeats.
std::vector<Eigen::VectorXd> StatedStarts(const std::vector<Eigen::VectorXd>& starts,
                                          const std::vector<EffectParameter>& defaults,
                                          const std::vector<EffectParameter>& stated) {
  std::vector<Eigen::VectorXd> out;
  auto add = [&](const Eigen::VectorXd& v) {
    for (const Eigen::VectorXd& o : out)
      if ((o - v).cwiseAbs().maxCoeff() <= 1e-12) return;
    out.push_back(v);
  };
  const Eigen::Index n = static_cast<Eigen::Index>(stated.size());
  for (Eigen::VectorXd s : starts) {
    for (Eigen::Index i = 0; i < n && i < s.size(); ++i)
      s[i] = std::clamp(s[i], stated[i].lower, stated[i].upper);
    add(s);
  }
  if (starts.empty() || starts.front().size() != n) return out;
  Eigen::VectorXd middle = out.front();
  bool changed = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    const EffectParameter& d = defaults[static_cast<std::size_t>(i)];
    const EffectParameter& p = stated[static_cast<std::size_t>(i)];
    if (p.normal_sigma > 0) {
      middle[i] = std::clamp(CoordinateOf(p, p.normal_mean), p.lower, p.upper);
      changed = true;
    } else if (p.lower != d.lower || p.upper != d.upper) {
      middle[i] = 0.5 * (p.lower + p.upper);
      changed = true;
    }
  }
  if (changed) add(middle);
  return out;
}

// A cantilever effect with stated priors.
class StatedEffect : public Effect {
 public:
  StatedEffect(std::unique_ptr<Effect> base, FamilyPrior prior)
      : base_(std::move(base)), prior_(std::move(prior)) {}
  std::string kind() const override { return base_->kind(); }
  std::vector<EffectParameter> Parameters(const CantileverSpec& nominal) const override {
    return ApplyFamilyPrior(base_->Parameters(nominal), prior_);
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec& nominal) const override {
    return StatedStarts(base_->Starts(nominal), base_->Parameters(nominal),
                        Parameters(nominal));
  }
  void Apply(const Eigen::VectorXd& theta, Immersion immersion, bool wet_only_added_mass,
             const CantileverSpec& nominal, CantileverSpec* spec) const override {
    base_->Apply(theta, immersion, wet_only_added_mass, nominal, spec);
  }
  EffectLocation Location(const CantileverSpec& nominal,
                          const Eigen::VectorXd& theta) const override {
    return base_->Location(nominal, theta);
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& nominal,
                                          const Eigen::VectorXd& theta) const override {
    return base_->Magnitudes(nominal, theta);
  }

 private:
  std::unique_ptr<Effect> base_;
  FamilyPrior prior_;
};

// A structure's effect instance with stated priors.
class StatedModelEffect : public ModelEffect {
 public:
  StatedModelEffect(std::unique_ptr<ModelEffect> base, const FamilyPrior& prior)
      : base_(std::move(base)), params_(ApplyFamilyPrior(base_->Parameters(), prior)) {
    starts_ = StatedStarts(base_->Starts(), base_->Parameters(), params_);
  }
  std::string kind() const override { return base_->kind(); }
  const EffectRegion& region() const override { return base_->region(); }
  std::vector<EffectParameter> Parameters() const override { return params_; }
  std::vector<Eigen::VectorXd> Starts() const override { return starts_; }
  ModelChange Change(const Eigen::VectorXd& theta, Immersion immersion) const override {
    return base_->Change(theta, immersion);
  }
  ModelChange Derivative(const Eigen::VectorXd& theta, int i,
                         Immersion immersion) const override {
    return base_->Derivative(theta, i, immersion);
  }
  EffectLocation Location(const Eigen::VectorXd& theta) const override {
    return base_->Location(theta);
  }
  std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& theta) const override {
    return base_->Magnitudes(theta);
  }

 private:
  std::unique_ptr<ModelEffect> base_;
  std::vector<EffectParameter> params_;
  std::vector<Eigen::VectorXd> starts_;
};

}  // namespace

const FamilyPrior* StatedPriors::Find(const std::string& kind) const {
  for (const FamilyPrior& f : families)
    if (f.kind == kind) return &f;
  return nullptr;
}

double StatedPriors::Weight(const std::string& kind) const {
  const auto it = weights.find(kind);
  return it == weights.end() ? 1.0 : it->second;
}

double LevelPrior(const StatedPriors& priors, const std::vector<std::string>& families,
                  std::size_t num_singles, std::size_t num_pairs) {
  const double levels = num_pairs > 0 ? 3.0 : 2.0;
  const double share = families.empty()       ? 1.0
                       : families.size() == 1 ? 1.0 / static_cast<double>(num_singles)
                                              : 1.0 / static_cast<double>(num_pairs);
  double weight = families.empty() ? priors.Weight("none") : 1.0;
  for (const std::string& k : families) weight *= priors.Weight(k);
  return weight * share / levels;
}

Invalid StatedPriors::Validate() const {
  std::set<std::string> kinds;
  for (const FamilyPrior& f : families) {
    const std::string where = "priors." + f.kind;
    if (f.kind.empty()) return {"priors", "a family without a name"};
    if (!kinds.insert(f.kind).second) return {where, "stated twice"};
    std::set<std::string> seen;
    for (const QuantityPrior& q : f.quantities) {
      const std::string at = where + "." + q.quantity;
      if (q.quantity.empty()) return {where, "a quantity without a name"};
      if (!seen.insert(q.quantity).second) return {at, "stated twice"};
      if (q.normal) {
        if (!std::isfinite(q.mean) || !std::isfinite(q.sigma))
          return {at, "normal: the mean and standard deviation must be finite"};
        if (!(q.sigma > 0))
          return {at, "normal: the standard deviation must be positive, found " +
                          Num(q.sigma)};
      } else {
        if (!std::isfinite(q.lower) || !std::isfinite(q.upper))
          return {at, "the range's ends must be finite"};
        if (q.lower > q.upper)
          return {at, "lower " + Num(q.lower) + " > upper " + Num(q.upper)};
        if (q.lower == q.upper)
          return {at, "lower = upper = " + Num(q.lower) +
                          " leaves nothing to fit (state a range, or a normal prior)"};
      }
    }
    std::set<std::string> names;
    for (std::size_t k = 0; k < f.regions.size(); ++k) {
      const std::string at = where + ".regions[" + std::to_string(k + 1) + "]";
      if (f.regions[k].empty()) return {at, "an empty name"};
      if (!names.insert(f.regions[k]).second)
        return {at, "'" + f.regions[k] + "' is listed twice"};
    }
  }
  for (const auto& [kind, w] : weights) {
    if (kind.empty()) return {"weights", "a family without a name"};
    if (!(w > 0) || !std::isfinite(w))
      return {"weights." + kind, "expected a positive finite weight, found " + Num(w)};
  }
  return {};
}

double QuantityAt(const EffectParameter& p, double theta) {
  return p.log_coordinate ? p.quantity_scale * std::exp(theta) : p.quantity_scale * theta;
}

double CoordinateOf(const EffectParameter& p, double quantity) {
  return p.log_coordinate ? std::log(quantity / p.quantity_scale)
                          : quantity / p.quantity_scale;
}

std::vector<EffectParameter> ApplyFamilyPrior(std::vector<EffectParameter> params,
                                              const FamilyPrior& prior) {
  for (const QuantityPrior& q : prior.quantities) {
    auto it = std::find_if(params.begin(), params.end(), [&](const EffectParameter& p) {
      return !p.quantity.empty() && p.quantity == q.quantity;
    });
    if (it == params.end()) {
      std::string list;
      for (const EffectParameter& p : params)
        if (!p.quantity.empty()) list += (list.empty() ? "" : ", ") + p.quantity;
      throw InputError(q.quantity, "not a quantity of " + prior.kind +
                                       " on this model (its quantities: " +
                                       (list.empty() ? "none" : list) + ")");
    }
    EffectParameter& p = *it;
    if (q.normal) {
      if (!InDomain(p, q.mean)) {
        throw InputError(q.quantity, "normal: the mean " + Num(q.mean) + " is outside " +
                                         Domain(p) + ", the values " + q.quantity +
                                         " can take");
      }
      double lo = q.mean - 6 * q.sigma, hi = q.mean + 6 * q.sigma;
      const double default_lo = QuantityAt(p, p.lower);
      const double default_hi = QuantityAt(p, p.upper);
      if (q.mean >= default_lo && q.mean <= default_hi) {
        lo = std::max(lo, default_lo);
        hi = std::min(hi, default_hi);
      }
      lo = std::max(lo, p.log_coordinate ? 0.01 * q.mean : p.quantity_min);
      hi = std::min(hi, p.quantity_max);
      p.lower = CoordinateOf(p, lo);
      p.upper = CoordinateOf(p, hi);
      p.normal_mean = q.mean;
      p.normal_sigma = q.sigma;
    } else {
      if (!InDomain(p, q.lower) || !InDomain(p, q.upper)) {
        throw InputError(q.quantity, "the range [" + Num(q.lower) + ", " + Num(q.upper) +
                                         "] is not within " + Domain(p) +
                                         ", the values " + q.quantity + " can take");
      }
      p.lower = CoordinateOf(p, q.lower);
      p.upper = CoordinateOf(p, q.upper);
      p.normal_mean = p.normal_sigma = 0;
    }
  }
  return params;
}

std::unique_ptr<Effect> WithFamilyPrior(std::unique_ptr<Effect> effect,
                                        const FamilyPrior& prior,
                                        const CantileverSpec& nominal) {
  ApplyFamilyPrior(effect->Parameters(nominal), prior);  // throws where it does not fit
  return std::make_unique<StatedEffect>(std::move(effect), prior);
}

std::unique_ptr<ModelEffect> WithFamilyPrior(std::unique_ptr<ModelEffect> effect,
                                             const FamilyPrior& prior) {
  return std::make_unique<StatedModelEffect>(std::move(effect), prior);
}

std::vector<std::unique_ptr<ModelEffect>> KeepStatedRegions(
    std::vector<std::unique_ptr<ModelEffect>> instances, const Structure& s,
    const FamilyPrior& prior) {
  if (prior.regions.empty()) return instances;
  if (instances.size() == 1) {
    throw InputError("regions", prior.kind + " has one place on this model (" +
                                    instances.front()->region().name +
                                    "): there is nothing to choose among");
  }
  std::vector<bool> keep(instances.size(), false);
  for (std::size_t k = 0; k < prior.regions.size(); ++k) {
    const std::string& name = prior.regions[k];
    bool found = false;
    for (std::size_t i = 0; i < instances.size(); ++i) {
      const EffectRegion& r = instances[i]->region();
      // A member by its label ("brace n8-n24"; its parts too), or the elements
      // and nodes it lies in.
      bool match =
          r.name == "member " + name ||
          (r.member >= 0 && s.members[static_cast<std::size_t>(r.member)].label == name);
      for (int e : r.elements) match = match || NamesElement(s.elements[e], name);
      for (int d : r.dofs) match = match || NodeOf(s.dof_labels[d]) == name;
      if (match) keep[i] = found = true;
    }
    if (found) continue;
    const bool element =
        std::any_of(s.elements.begin(), s.elements.end(),
                    [&](const ElementMatrices& e) { return NamesElement(e, name); });
    const bool node =
        std::any_of(s.dof_labels.begin(), s.dof_labels.end(),
                    [&](const std::string& label) { return NodeOf(label) == name; });
    const bool member =
        std::any_of(s.members.begin(), s.members.end(),
                    [&](const ElementMember& m) { return m.label == name; });
    const std::string first = instances.front()->region().name;
    const char* what = member    ? "a member"
                       : element ? "an element"
                       : node    ? "a node"
                                 : "";
    const std::string why =
        *what ? std::string("names ") + what + ", but " + prior.kind +
                    " acts at places such as '" + first + "'"
              : "names no element (1-based id or label), member or node of this model";
    throw InputError("regions[" + std::to_string(k + 1) + "]", "'" + name + "' " + why);
  }
  std::vector<std::unique_ptr<ModelEffect>> out;
  for (std::size_t i = 0; i < instances.size(); ++i)
    if (keep[i]) out.push_back(std::move(instances[i]));
  return out;
}

int NumPriorResiduals(const std::vector<EffectParameter>& params) {
  return static_cast<int>(
      std::count_if(params.begin(), params.end(),
                    [](const EffectParameter& p) { return p.normal_sigma > 0; }));
}

NonlinearProblem WithPriorResiduals(NonlinearProblem problem,
                                    const std::vector<EffectParameter>& params) {
  const int m = NumPriorResiduals(params);
  if (m == 0) return problem;
  if (static_cast<int>(params.size()) != problem.num_parameters()) {
    throw InputError("priors", std::to_string(params.size()) +
                                   " parameters for a fit of " +
                                   std::to_string(problem.num_parameters()));
  }
  const int n_data = problem.num_residuals;
  problem.num_residuals += m;
  if (!problem.residual_labels.empty()) {
    for (const EffectParameter& p : params)
      if (p.normal_sigma > 0) problem.residual_labels.push_back("prior " + p.quantity);
  }
  const NonlinearProblem::Evaluate data = problem.evaluate;
  problem.evaluate = [data, params, n_data, m](const Eigen::VectorXd& x,
                                               Eigen::VectorXd* r, Eigen::MatrixXd* jac,
                                               std::string* why) {
    Eigen::VectorXd rd;
    Eigen::MatrixXd jd;
    if (!data(x, &rd, jac != nullptr ? &jd : nullptr, why)) return false;
    if (rd.size() != n_data || (jac != nullptr && jd.rows() != n_data)) {
      if (why) *why = "the data's residuals changed size";
      return false;
    }
    r->resize(n_data + m);
    r->head(n_data) = rd;
    if (jac != nullptr) {
      jac->setZero(n_data + m, x.size());
      jac->topRows(n_data) = jd;
    }
    int k = n_data;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const EffectParameter& p = params[i];
      if (!(p.normal_sigma > 0)) continue;
      const Eigen::Index col = static_cast<Eigen::Index>(i);
      const double q = QuantityAt(p, x[col]);
      (*r)[k] = (q - p.normal_mean) / p.normal_sigma;
      if (jac != nullptr)
        (*jac)(k, col) = (p.log_coordinate ? q : p.quantity_scale) / p.normal_sigma;
      ++k;
    }
    return true;
  };
  return problem;
}

void LocalNormalPriors(const std::vector<EffectParameter>& params,
                       const Eigen::VectorXd& theta, Eigen::VectorXd* mean,
                       Eigen::VectorXd* sigma) {
  mean->resize(0);
  sigma->resize(0);
  if (NumPriorResiduals(params) == 0) return;
  if (theta.size() != static_cast<Eigen::Index>(params.size())) {
    throw InputError("priors", std::to_string(params.size()) + " parameters for " +
                                   std::to_string(theta.size()) + " values");
  }
  mean->setZero(theta.size());
  sigma->setZero(theta.size());
  for (Eigen::Index i = 0; i < theta.size(); ++i) {
    const EffectParameter& p = params[static_cast<std::size_t>(i)];
    if (!(p.normal_sigma > 0)) continue;
    // dq/dtheta at theta; the Gaussian in theta with the same residual and the
    // same slope.
    const double q = QuantityAt(p, theta[i]);
    const double slope = p.log_coordinate ? q : p.quantity_scale;
    (*sigma)[i] = p.normal_sigma / std::abs(slope);
    (*mean)[i] = theta[i] - (q - p.normal_mean) / slope;
  }
}

}  // namespace femup
