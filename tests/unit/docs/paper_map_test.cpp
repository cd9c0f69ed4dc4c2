// docs/paper-map.md maps the paper's sections and equations to the code. Every backticked
// `path:function` reference in it (and every backticked path ending in .cpp/.hpp) must name a
// file under the source root that contains the function as an identifier outside comments, every
// table row must carry at least one reference, and a document without references fails.

#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#ifndef TOURMAP_SOURCE_DIR
#error "TOURMAP_SOURCE_DIR must name the source root (tests/CMakeLists.txt defines it)"
#endif

namespace tourmap::test {
namespace {

namespace fs = std::filesystem;

struct Reference {
  int line = 0;      // 1-based line in the document
  std::string text;  // the backticked text
  std::string path;  // relative to the source root
  std::string name;  // empty for a plain path
};

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

bool is_identifier_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

// `src` with // and /* */ comments replaced by a space. String, character and raw string literals
// are kept (a GLSL source in a raw string is code), and comment markers inside them do not count.
std::string strip_comments(const std::string& src) {
  std::string out;
  out.reserve(src.size());
  const std::size_t n = src.size();
  std::size_t i = 0;
  while (i < n) {
    const char c = src[i];
    const char next = i + 1 < n ? src[i + 1] : '\0';
    if (c == '/' && next == '/') {
      while (i < n && src[i] != '\n') ++i;
      out += ' ';
    } else if (c == '/' && next == '*') {
      const std::size_t end = src.find("*/", i + 2);
      i = end == std::string::npos ? n : end + 2;
      out += ' ';
    } else if (c == '"' && i > 0 && src[i - 1] == 'R' &&
               (i < 2 || !is_identifier_char(src[i - 2]) || src[i - 2] == '8' || src[i - 2] == 'u' ||
                src[i - 2] == 'U' || src[i - 2] == 'L')) {
      // Raw string R"delim( ... )delim": copied as is.
      const std::size_t open = src.find('(', i + 1);
      if (open == std::string::npos) {
        out.append(src, i, std::string::npos);
        break;
      }
      const std::string close = ")" + src.substr(i + 1, open - i - 1) + "\"";
      const std::size_t end = src.find(close, open + 1);
      const std::size_t stop = end == std::string::npos ? n : end + close.size();
      out.append(src, i, stop - i);
      i = stop;
    } else if (c == '"' || (c == '\'' && (i == 0 || !is_identifier_char(src[i - 1])))) {
      // A string or character literal (a ' after a digit is a digit separator). A newline ends
      // an unterminated one, so a stray quote cannot hide the rest of the file.
      out += c;
      ++i;
      while (i < n && src[i] != c && src[i] != '\n') {
        if (src[i] == '\\' && i + 1 < n) out += src[i++];
        out += src[i++];
      }
      if (i < n) out += src[i++];
    } else {
      out += c;
      ++i;
    }
  }
  return out;
}

// Whether `name` occurs in `code` as a whole identifier (qualified names and operators as written).
bool has_identifier(const std::string& code, const std::string& name) {
  for (std::size_t pos = code.find(name); pos != std::string::npos; pos = code.find(name, pos + 1)) {
    const bool starts = pos == 0 || !is_identifier_char(code[pos - 1]);
    const std::size_t end = pos + name.size();
    const bool ends = !is_identifier_char(name.back()) || end == code.size() || !is_identifier_char(code[end]);
    if (starts && ends) return true;
  }
  return false;
}

// Backticked spans that are source references: "path.cpp", "path.hpp" or "path.cpp:name".
std::vector<Reference> extract_references(const std::string& doc) {
  static const std::regex span("`([^`\n]+)`");
  static const std::regex source(R"(^([A-Za-z0-9_./-]+\.(?:cpp|hpp|cc|h))(?::(.*))?$)");
  std::vector<Reference> refs;
  std::istringstream in(doc);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    for (std::sregex_iterator it(line.begin(), line.end(), span), end; it != end; ++it) {
      const std::string text = (*it)[1].str();
      std::smatch m;
      if (!std::regex_match(text, m, source)) continue;
      refs.push_back({number, text, m[1].str(), m[2].matched ? m[2].str() : std::string()});
      if (m[2].matched && refs.back().name.empty()) refs.back().name = ":";  // "file.cpp:" is malformed
    }
  }
  return refs;
}

// Empty when the reference resolves, else what is wrong with it.
std::string check_reference(const Reference& ref, const fs::path& root) {
  static const std::regex name_syntax(
      R"(^(?:[A-Za-z_][A-Za-z0-9_]*::)*(?:~?[A-Za-z_][A-Za-z0-9_]*|operator(?:\(\)|\[\]|[-+*/%^&|~!=<>]+))$)");
  const fs::path rel(ref.path);
  if (rel.is_absolute() || ref.path.find("..") != std::string::npos) return "path must be relative to the source root";
  const fs::path file = root / rel;
  if (!fs::is_regular_file(file)) return "no such file " + file.string();
  if (ref.name.empty()) return "";
  if (!std::regex_match(ref.name, name_syntax)) return "'" + ref.name + "' is not a function name";
  const auto text = read_text(file);
  if (!text) return "cannot read " + file.string();
  if (!has_identifier(strip_comments(*text), ref.name))
    return "'" + ref.name + "' does not occur in " + ref.path + " (outside comments)";
  return "";
}

bool is_separator_row(const std::string& line) {
  return line.rfind("|", 0) == 0 && line.find_first_not_of("|-: \t") == std::string::npos;
}

// Every problem with the document: unresolved references, table rows without a reference, and a
// document without any reference at all.
std::vector<std::string> check_paper_map(const std::string& doc, const fs::path& root, std::size_t* checked = nullptr) {
  std::vector<std::string> problems;
  const auto refs = extract_references(doc);
  if (checked) *checked = refs.size();
  if (refs.empty()) problems.push_back("no `path:function` references at all");
  for (const auto& ref : refs) {
    const std::string problem = check_reference(ref, root);
    if (!problem.empty()) problems.push_back("line " + std::to_string(ref.line) + ": `" + ref.text + "`: " + problem);
  }
  // Data rows are the table rows after a separator row, up to the first line outside the table.
  static const std::regex any_reference(R"(`[A-Za-z0-9_./-]+\.(?:cpp|hpp|cc|h)(?::[^`]*)?`)");
  std::istringstream in(doc);
  std::string line;
  bool in_body = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("|", 0) != 0) {
      in_body = false;
    } else if (is_separator_row(line)) {
      in_body = true;
    } else if (in_body && !std::regex_search(line, any_reference)) {
      problems.push_back("line " + std::to_string(number) + ": table row without a code reference: " + line);
    }
  }
  return problems;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += "  " + l + "\n";
  return out;
}

TEST(PaperMap, EveryReferenceResolves) {
  const fs::path root(TOURMAP_SOURCE_DIR);
  const auto doc = read_text(root / "docs" / "paper-map.md");
  ASSERT_TRUE(doc) << "cannot read " << (root / "docs" / "paper-map.md");
  std::size_t checked = 0;
  const auto problems = check_paper_map(*doc, root, &checked);
  EXPECT_GT(checked, 0u);
  EXPECT_TRUE(problems.empty()) << problems.size() << " problem(s) in docs/paper-map.md (" << checked
                                << " references checked):\n"
                                << joined(problems);
}

// The checker itself, on a small source tree of its own: it must report exactly the broken
// references, so that the test above cannot pass by accepting anything.
class PaperMapChecker : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("paper_map_test_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    fs::create_directories(root_ / "src");
    std::ofstream(root_ / "src" / "a.cpp") << "// only_in_line_comment()\n"
                                              "/* only_in_block_comment()\n   spans lines */\n"
                                              "const char* s = \"text // after_slashes_in_string\";\n"
                                              "const char* glsl = R\"(vec3 shader_function(float t) { })\";\n"
                                              "int separated = 1'000'000;  // digit separators are no quotes\n"
                                              "int real_function(int x) { return x; }\n"
                                              "struct Widget { void run(); bool operator()() const; };\n"
                                              "void Widget::run() {}\n"
                                              "bool Widget::operator()() const { return true; }\n";
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  fs::path root_;
};

TEST_F(PaperMapChecker, ReportsExactlyTheBrokenReferences) {
  const std::string doc =
      "| paper | what | implemented in | notes |\n"
      "|---|---|---|---|\n"
      "| 1 | ok | `src/a.cpp:real_function`, `src/a.cpp` | |\n"
      "| 2 | ok | `src/a.cpp:Widget::run`, `src/a.cpp:Widget::operator()` | |\n"
      "| 3 | ok | `src/a.cpp:after_slashes_in_string`, `src/a.cpp:shader_function` | |\n"
      "| 4 | bad | `src/a.cpp:only_in_line_comment` | |\n"
      "| 5 | bad | `src/a.cpp:only_in_block_comment` | |\n"
      "| 6 | bad | `src/missing.cpp:f`, `src/missing.hpp` | |\n"
      "| 7 | bad | `src/a.cpp:real` | part of an identifier |\n"
      "| 8 | bad | `src/a.cpp:1bad`, `src/a.cpp:` | |\n"
      "| 9 | bad | `../a.cpp:real_function` | |\n"
      "| 10 | bad | no reference | |\n"
      "\n"
      "Prose `src/a.cpp:Widget` outside a table is checked too; `eq. 4.2` is not a reference.\n";
  std::size_t checked = 0;
  const auto problems = check_paper_map(doc, root_, &checked);
  EXPECT_EQ(checked, 15u);
  const std::vector<std::string> broken = {"`src/a.cpp:only_in_line_comment`",
                                           "`src/a.cpp:only_in_block_comment`",
                                           "`src/missing.cpp:f`",
                                           "`src/missing.hpp`",
                                           "`src/a.cpp:real`",
                                           "`src/a.cpp:1bad`",
                                           "`src/a.cpp:`",
                                           "`../a.cpp:real_function`",
                                           "| 10 | bad | no reference | |"};
  EXPECT_EQ(problems.size(), broken.size()) << joined(problems);
  for (const auto& b : broken) {
    bool reported = false;
    for (const auto& p : problems) reported = reported || p.find(b) != std::string::npos;
    EXPECT_TRUE(reported) << b << " was not reported; problems:\n" << joined(problems);
  }
}

TEST_F(PaperMapChecker, FailsWithoutReferences) {
  const auto problems = check_paper_map("# Paper map\n\nNothing mapped yet.\n", root_);
  ASSERT_EQ(problems.size(), 1u) << joined(problems);
  EXPECT_NE(problems[0].find("no `path:function` references"), std::string::npos);
}

}  // namespace
}  // namespace tourmap::test
