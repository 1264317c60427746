// The corpus of hostile inputs, tests/corpus/<case>/: each case's command run by the vdcloth
// program in a copy of the corpus, its exit status and the words of its message checked, and,
// when the input is refused, a one-line message and nothing written. Cases are described in
// tests/corpus/README.md.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vdc {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(VDCLOTH_SOURCE_DIR) / "tests" / "corpus";

struct Outcome {
  int status = -1;     // exit status, or 128 + the signal that ended the program
  std::string output;  // standard output (progress) and standard error (messages), in that order
  std::string errors;  // standard error alone
};

std::string contents(const fs::path& path) {
  std::ostringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

// Runs the vdcloth program with `args` in directory `cwd`; its output goes to `log` (standard
// output) and `log`.err (standard error).
Outcome run_vdcloth(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& log) {
  const fs::path error_log = log.string() + ".err";
  std::vector<std::string> argv_strings = {VDCLOTH_BINARY};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int error_fd = ::open(error_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || error_fd < 0 || ::chdir(cwd.c_str()) != 0 || ::dup2(fd, 1) < 0 || ::dup2(error_fd, 2) < 0) ::_exit(127);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  Outcome outcome;
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid) return outcome;
  outcome.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  outcome.errors = contents(error_log);
  outcome.output = contents(log) + outcome.errors;
  return outcome;
}

// Every file and directory under `root` with its size and modification time: what a command
// wrote, moved or removed shows as a difference.
std::map<std::string, std::string> tree(const fs::path& root) {
  std::map<std::string, std::string> entries;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string path = fs::relative(e.path(), root).string();
    if (e.is_directory()) entries[path] = "directory";
    else entries[path] = std::to_string(e.file_size()) + " bytes, written " + std::to_string(e.last_write_time().time_since_epoch().count());
  }
  return entries;
}

// The case's `damage`: a file made by its `before` commands removed, cut short, a byte of it
// inverted, or text appended.
void damage(const fs::path& dir, const nlohmann::json& d) {
  const fs::path file = dir / d.at("file").get<std::string>();
  if (d.value("remove", false)) {
    fs::remove(file);
    return;
  }
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (d.contains("keep_bytes")) bytes.resize(std::min(bytes.size(), d.at("keep_bytes").get<std::size_t>()));
  if (d.contains("flip_byte")) bytes.at(d.at("flip_byte").get<std::size_t>()) ^= static_cast<char>(0xff);
  bytes += d.value("append", std::string());
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kCorpus))
    if (fs::exists(e.path() / "case.json")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class CorpusCase : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("vdcloth_corpus_" + std::to_string(::getpid()) + "_" + GetParam());
    fs::remove_all(root_);
    // The case, the files cases share and the unit tests' data, which cases may name.
    fs::create_directories(root_ / "corpus");
    fs::copy(kCorpus / GetParam(), root_ / "corpus" / GetParam(), fs::copy_options::recursive);
    fs::copy(kCorpus / "common", root_ / "corpus" / "common", fs::copy_options::recursive);
    fs::copy(VDCLOTH_TEST_DATA, root_ / "data", fs::copy_options::recursive);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_P(CorpusCase, ExitsAsExpectedNamingTheProblem) {
  const fs::path dir = root_ / "corpus" / GetParam();
  const nlohmann::json spec = nlohmann::json::parse(std::ifstream(dir / "case.json"));
  SCOPED_TRACE(GetParam() + ": " + spec.at("about").get<std::string>());
  const fs::path log = root_ / "log.txt";
  for (const auto& before : spec.value("before", nlohmann::json::array())) {
    const Outcome made = run_vdcloth(before.get<std::vector<std::string>>(), dir, log);
    ASSERT_EQ(made.status, 0) << "a command that prepares the case failed:\n" << made.output;
  }
  if (spec.contains("damage")) damage(dir, spec.at("damage"));
  const auto before = tree(root_ / "corpus");

  const Outcome got = run_vdcloth(spec.at("args").get<std::vector<std::string>>(), dir, log);

  EXPECT_EQ(got.status, spec.at("exit").get<int>()) << got.output;
  for (const auto& word : spec.at("words")) EXPECT_NE(got.output.find(word.get<std::string>()), std::string::npos) << "no '" << word << "' in\n" << got.output;
  if (got.status == 2) {
    EXPECT_EQ(tree(root_ / "corpus"), before) << "a refused input wrote or removed files";
    if (spec.value("one_line", true)) {  // progress before it may go to standard output
      EXPECT_EQ(std::count(got.errors.begin(), got.errors.end(), '\n'), 1) << got.errors;
      EXPECT_LE(got.errors.size(), 600u) << "a message too long to read";
      EXPECT_EQ(got.errors.rfind("vdcloth: ", 0), 0u) << got.errors;
    }
  }
}

std::string case_test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, CorpusCase, ::testing::ValuesIn(case_names()), case_test_name);

}  // namespace
}  // namespace vdc
