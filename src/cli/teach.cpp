#include "teach.hpp"

#include <ostream>

#include "core/dry_run/teach.hpp"
#include "inputs.hpp"
#include "io/file_writer.hpp"
#include "io/files.hpp"

namespace fatc::io {

int teach_position(const Options& options, std::ostream& out, std::ostream& err) {
  try {
    const FileWriter config(options.config_path, kCommandLineWait);
    std::string error;
    const auto text = read_small_file(options.config_path, error);
    if (!text) {
      err << error << "\n";
      return 2;
    }
    std::optional<SoftLimits> limits;
    if (options.ini_path) {
      int problems = 0;  // said; a teach needs only the limits
      limits = read_limits(*options.ini_path, declared_units(*text), err, problems);
      if (!limits) return 2;
    }
    TableRead table = read_table(options, declared_units(*text));
    if (!table.error.empty() && options.tool_table_path) {
      err << table.error << "\n";
      return 2;
    }
    ToolLengths lengths;
    lengths.table = std::move(table.lengths);
    const TeachResult taught =
        teach(*text, *options.teach_target, *options.teach_at, limits, lengths);
    if (!taught.text) {
      err << shown_path(options.config_path) << ": " << taught.error << "\n";
      return 1;
    }
    save_config_file(config, *text, *taught.text, kCommandLineWait);
    out << taught.change << "\n"
        << "written (previous file kept as " << shown_path(options.config_path + ".bak") << ")\n";
    return 0;
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 2;
  }
}

}  // namespace fatc::io
