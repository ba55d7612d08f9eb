#include "deploy/fleet/host_files.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include "deploy/fleet/hosts.hpp"
#include "records/csv.hpp"

namespace maptr::deploy::fleet {

namespace fs = std::filesystem;

namespace {
constexpr const char* kOwnMark = "maptr-own";
constexpr const char* kSharedMark = "maptr-shared";

std::string first_line(const std::string& text) {
  const auto start = text.find_first_not_of("\r\n");
  if (start == std::string::npos) return "";
  return text.substr(start, text.find_first_of("\r\n", start) - start);
}

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Appends `text` to `path`: a CSV file's rows (records/csv.hpp), a log's lines.
void append(const fs::path& path, const std::string& text) {
  if (path.extension() == ".csv")
    records::append_csv_rows(path.string(), text);
  else
    std::ofstream(path, std::ios::binary | std::ios::app) << text;
}
}  // namespace

std::string ship_run_files(const std::vector<std::string>& prefix, const std::string& run_dir,
                           const std::vector<std::pair<std::string, std::string>>& files, HostDisk& disk) {
  disk = HostDisk::kSame;
  if (prefix.empty()) return "";
  const std::string script =
      std::string("d=$1; shift; if test -e \"$d/") + kLauncherMarker + "\"; then echo " + kSharedMark +
      "; exit 0; fi; mkdir -p \"$d/logs\" || exit 1; " +
      "while test $# -gt 1; do printf %s \"$2\" > \"$d/$1\" || exit 1; shift 2; done; echo " + kOwnMark;
  std::vector<std::string> args = {"-c", script, "sh", run_dir};
  for (const auto& [path, content] : files) {
    args.push_back(path);
    args.push_back(content);
  }
  std::string out;
  const int rc = run_tool(host_argv(prefix, {}, "sh", args, false), &out);
  if (rc == 0 && out.find(kSharedMark) != std::string::npos) {
    disk = HostDisk::kShared;
    return "";
  }
  if (rc == 0 && out.find(kOwnMark) != std::string::npos) {
    disk = HostDisk::kOwn;
    return "";
  }
  const std::string why = first_line(out);
  return "cannot write its run folder " + run_dir + " (exit " + std::to_string(rc) +
         (why.empty() ? "" : ": " + why) + ")";
}

std::string collect_run_files(const std::vector<std::string>& prefix, const std::string& run_dir,
                              const std::string& name, const std::vector<std::string>& shipped) {
  std::vector<std::string> args = {"-c", "cd \"$1\" && shift && exec tar -czf - \"$@\" . 2>/dev/null", "sh",
                                   run_dir};
  for (const auto& f : shipped) args.push_back("--exclude=./" + f);
  std::string tgz;
  const int rc = run_tool(host_argv(prefix, {}, "sh", args, false), &tgz, false);
  if (rc != 0 || tgz.empty())
    return "not collected: the copy over its command prefix ended with exit " + std::to_string(rc) +
           " (a lost or cut-off host cannot be reached)";
  const fs::path dir = fs::path(run_dir) / "hosts" / name;
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  const fs::path archive = dir.string() + ".tgz";
  std::ofstream(archive, std::ios::binary) << tgz;
  std::string out;
  const int x = run_tool({"tar", "-xzf", archive.string(), "-C", dir.string()}, &out);
  fs::remove(archive, ec);
  if (x != 0) return "not collected: tar could not unpack the copy (" + first_line(out) + ")";
  return "collected " + std::to_string(merge_host_folder(dir.string(), run_dir)) + " files";
}

int merge_host_folder(const std::string& from, const std::string& run_dir) {
  int taken = 0;
  for (const auto& e : fs::recursive_directory_iterator(from)) {
    if (!e.is_regular_file()) continue;
    const fs::path dest = fs::path(run_dir) / fs::relative(e.path(), from);
    const std::string ext = dest.extension().string();
    if (!fs::exists(dest)) {
      fs::create_directories(dest.parent_path());
      fs::copy_file(e.path(), dest);
    } else if (ext == ".csv" || ext == ".log" || ext == ".stderr") {
      append(dest, file_text(e.path()));
    } else {
      continue;
    }
    ++taken;
  }
  return taken;
}

}  // namespace maptr::deploy::fleet
