// femup check: read and check a study file, print what it describes.
#include "commands.h"

namespace femup::cli {

Command CheckCommand() {
  auto study_file = std::make_shared<std::string>();
  return {"check", "read and check a study file, do no work",
          [study_file](CLI::App* cmd) { AddStudyFile(cmd, study_file.get()); },
          [study_file](const Invocation&) {
            const femup::Study study = femup::LoadStudy(*study_file);
            std::cout << *study_file << ": ok: " << study.structure.description << ", "
                      << study.model.num_dofs() << " DOFs, "
                      << study.model.num_parameters() << " parameters, "
                      << study.measurements.size() << " measured state(s)\n";
            return 0;
          }};
}

}  // namespace femup::cli
