#include "config_teacher.hpp"

#include "io/files.hpp"

namespace fatc::linuxcnc {

void ConfigTeacher::teach(Changer& changer, const TeachTarget& target, bool linuxcnc_status,
                          const std::optional<Point>& at) {
  const std::string request = "teach " + target_name(target);
  if (const auto why = changer.why_not_teach(linuxcnc_status, at)) {
    ports_.tell(MessageKind::error, request + " refused: " + *why);
    return;
  }
  write(changer, request, [&](const std::string& text) {
    return fatc::teach(text, target, *at, limits_, changer.keepout_lengths());
  });
}

void ConfigTeacher::write_found(Changer& changer, const std::vector<Found>& found, bool datum) {
  const std::string request = datum ? "teach the rack datum" : "teach by touch";
  std::vector<Taught> taught;
  for (const Found& each : found) {
    taught.push_back({{datum ? TeachTarget::Kind::datum : TeachTarget::Kind::pocket, each.pocket},
                      each.at});
  }
  write(changer, request, [&](const std::string& text) {
    return teach_all(text, taught, limits_, changer.keepout_lengths());
  });
}

void ConfigTeacher::write(Changer& changer, const std::string& request,
                          const std::function<TeachResult(const std::string&)>& make) {
  const std::string refused = request + " refused: ";
  // Taken before it is read: a --teach at the same time waits its turn, and
  // this one reads what it wrote. Held briefly: the poll loop waits on it.
  std::optional<io::FileWriter> file;
  try {
    file.emplace(config_path_, io::kComponentWait);
  } catch (const std::exception& e) {
    ports_.tell(MessageKind::error, refused + e.what());
    return;
  }
  std::string error;
  const auto text = io::read_small_file(config_path_, error);
  if (!text) {
    ports_.tell(MessageKind::error, refused + error);
    return;
  }
  const TeachResult taught = make(*text);
  if (!taught.text) {
    ports_.tell(MessageKind::error, taught.error);
    return;
  }
  // Taken before it is written: a changer that refuses it (saying why) leaves
  // the file as it was, and one that took it runs what the file will hold.
  const Config before = changer.config();
  if (!changer.reconfigure(*parse_config(*taught.text).config, request)) return;
  try {
    io::save_config_file(*file, *text, *taught.text, io::kComponentWait);
  } catch (const std::exception& e) {
    // Still idle: nothing ran since it was taken, so the old one goes back in.
    changer.reconfigure(before, request);
    ports_.tell(MessageKind::error, refused + e.what());
    return;
  }
  ports_.tell(MessageKind::info, "taught " + taught.change + "; " + io::shown_path(config_path_) +
                                     " written, the previous one kept as " +
                                     io::shown_path(config_path_ + ".bak"));
}

}  // namespace fatc::linuxcnc
