// femup info: describe a data file (UFF, CSV time series, Matrix Market).
#include "commands.h"
#include "femup/studies/file_info.h"

namespace femup::cli {

namespace {

struct InfoOptions {
  std::string file;
  bool json = false;
};

}  // namespace

Command InfoCommand() {
  auto o = std::make_shared<InfoOptions>();
  return {
      "info",
      "describe a data file: a UFF file's datasets (58 functions, 55 mode shapes, "
      "15/2411 nodes), a CSV time series' channels, a Matrix Market matrix",
      [o](CLI::App* cmd) {
        cmd->add_option("file", o->file, "a .uff, .unv, .csv or .mtx file")->required();
        cmd->add_flag("--json", o->json, "print JSON instead of text");
      },
      [o](const Invocation&) {
        const femup::FileInfo described = femup::DescribeFile(o->file);
        std::cout << (o->json ? femup::FileInfoJson(described)
                              : femup::FileInfoReport(described));
        return 0;
      }};
}

}  // namespace femup::cli
