// Identifies the paper chain's factors through the installed library.
#include <cmath>
#include <cstdio>

#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"

int main() {
  const femup::PaperChainScenario s = femup::PaperChain(3);
  const femup::Modes fem = femup::SolveModes(s.model.stiffness(), s.model.mass());
  std::vector<femup::ModalData> states = {
      femup::PredictModes(s.model, s.preset, femup::Immersion::kDry, 2, "air"),
      femup::PredictModes(s.model, s.preset, femup::Immersion::kWet, 2, "water")};
  femup::LinearProblem p = femup::BuildCorrectionSystem(s.model, fem, states, {});
  p.Fix("mass[4]", 0.0058);
  const femup::LinearSolution sol = femup::CreateLinearSolver("lstsq")->Solve(p);
  const double err = (sol.x - s.preset).cwiseAbs().maxCoeff();
  std::printf("f1 = %.2f Hz, max factor error %.1e\n", fem.FrequenciesHz()[0], err);
  return err < 1e-10 ? 0 : 1;
}
