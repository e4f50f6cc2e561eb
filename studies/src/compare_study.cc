#include "femup/studies/compare_study.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/studies/study.h"

namespace femup {

CompareResult RunCompare(const std::vector<std::string>& study_paths) {
  if (study_paths.size() < 2)
    throw InputError("compare", "give at least two study files to compare");
  CompareResult r;
  r.paths = study_paths;
  for (const std::string& path : study_paths) {
    const Study study = LoadStudy(path);
    if (study.measurements.empty())
      throw InputError(path, "measurements: missing (nothing to update)");
    r.updates.push_back(RunUpdate(study));
    std::vector<double> x0, x1, f;
    const Eigen::VectorXd& d = r.updates.back().solution.x;
    for (int i : study.model.ParametersOfKind(ParameterKind::kAddedMass)) {
      for (int e : study.model.parameter(i).elements) {
        // A space frame's factors list geometry elements, not the Structure's
        // groups (space_frame.h): no element length to take from it.
        const int k =
            study.structure.type == "space_frame" ? -1 : study.structure.FindElement(e);
        if (k < 0) continue;
        x0.push_back(study.structure.elements[k].x0);
        x1.push_back(study.structure.elements[k].x1);
        f.push_back(d[i]);
      }
    }
    r.element_x0.push_back(x0);
    r.element_x1.push_back(x1);
    r.element_factor.push_back(f);
  }
  return r;
}

}  // namespace femup
