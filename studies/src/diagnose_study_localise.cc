// The localisation scan of a diagnosis (diagnose_study_steps.h): every
// element's bending stiffness and its mass changed alone, each by one fitted
// factor, and the chi2 drop each achieves.
#include <algorithm>
#include <cmath>

#include "diagnose_study_steps.h"

namespace femup::diagnose_steps {
namespace {

// One element's bending stiffness (EI times 1 + factor) or an added transverse
// mass (factor times rho A) over the element: the localisation scan's classes.
class ElementChange : public Effect {
 public:
  ElementChange(bool stiffness, double z0, double z1)
      : stiffness_(stiffness), z0_(z0), z1_(z1) {}
  std::string kind() const override {
    return stiffness_ ? "element_stiffness" : "element_mass";
  }
  std::vector<EffectParameter> Parameters(const CantileverSpec&) const override {
    if (stiffness_) return {{"factor", "EI change (fraction)", -0.95, 3.0, false}};
    return {{"factor", "added mass (fraction of rho A)", 0.0, 10.0, false}};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec&) const override {
    return {Eigen::VectorXd::Constant(1, stiffness_ ? 0.0 : 0.01)};
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    if (stiffness_) {
      CantileverSpec::StiffnessChange c;
      c.z0 = z0_;
      c.z1 = z1_;
      c.factor = t[0];
      if (t[0] != 0) spec->stiffness_changes.push_back(c);
    } else if (t[0] > 0) {
      CantileverSpec::DistributedMass m;
      m.z0 = z0_;
      m.z1 = z1_;
      m.mass_per_length = t[0] * BeamMassPerLength(nominal);
      spec->distributed_masses.push_back(m);
    }
  }
  EffectLocation Location(const CantileverSpec&, const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x0 = z0_;
    l.x1 = z1_;
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec&,
                                          const Eigen::VectorXd& t) const override {
    return {{"factor", "1", t[0]}};
  }

 private:
  bool stiffness_;
  double z0_, z1_;
};

}  // namespace

void LocaliseByElement(const DiagnosisSpec& spec, const CantileverSpec& nominal,
                       const NonlinearSolver& solver, DiagnosisResult* result) {
  DiagnosisResult& r = *result;
  if (spec.localise) {
    const double chi2_nominal =
        EffectResiduals(r.fitted_data, r.nominal_fitted).squaredNorm();
    for (std::size_t e = 0; e + 1 < nominal.node_heights.size(); ++e) {
      ElementIndicator ind;
      ind.element = static_cast<int>(e + 1);
      ind.x0 = nominal.node_heights[e];
      ind.x1 = nominal.node_heights[e + 1];
      for (bool stiffness : {true, false}) {
        const ElementChange change(stiffness, ind.x0, ind.x1);
        int runs = 0;
        const FitOutcome fit =
            FitClass(r.fitted_data, {&change}, change.Starts(nominal), solver, &runs);
        const double drop = fit.ok ? std::max(0.0, chi2_nominal - fit.chi2) : 0.0;
        const double factor = fit.ok ? fit.theta[0] : NAN;
        (stiffness ? ind.stiffness_chi2_drop : ind.mass_chi2_drop) = drop;
        (stiffness ? ind.stiffness_factor : ind.mass_factor) = factor;
      }
      r.localisation.push_back(ind);
    }
  }
}

}  // namespace femup::diagnose_steps
