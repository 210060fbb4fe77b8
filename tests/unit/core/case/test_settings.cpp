// Case-file settings: values, defaults, and errors that name the file, line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/case/settings.hpp"
#include "core/case/suggest.hpp"

using cocopp::CaseError;
using cocopp::Settings;

namespace {

/// The message of the CaseError `f` throws ("" if none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

/// The message of the CaseError loading `text` as the file `name` throws ("" if none).
std::string loading_error(const std::string& text, const std::string& name) {
  return error_of([&] { Settings::load_string(text, name); });
}

const char* kYaml = R"(settings:
  delta_t: 0.001
  number_of_timesteps: 10
coupled_solver:
  type: iqni
  omega: fast
  model:
    type: ls
    q: 10
)";

}  // namespace

TEST(Settings, ReadsValuesAndDefaults) {
  const Settings root = Settings::load_string(kYaml, "case.yaml");
  const Settings run = root.child("settings");
  EXPECT_DOUBLE_EQ(run.required<double>("delta_t"), 0.001);
  EXPECT_EQ(run.required<int>("number_of_timesteps"), 10);
  EXPECT_EQ(run.get<int>("timestep_start", 7), 7);
  EXPECT_EQ(root.child("coupled_solver").child("model").get<int>("q", 0), 10);
  EXPECT_EQ(root.child("coupled_solver").path(), "coupled_solver");
}

TEST(Settings, WrongTypeNamesFileLineAndKey) {
  const Settings root = Settings::load_string(kYaml, "case.yaml");
  const std::string message =
      error_of([&] { root.child("coupled_solver").get<double>("omega", 0.1); });
  EXPECT_NE(message.find("case.yaml:6:"), std::string::npos) << message;
  EXPECT_NE(message.find("'coupled_solver.omega'"), std::string::npos) << message;
  EXPECT_NE(message.find("expected a number, got 'fast'"), std::string::npos) << message;
}

TEST(Settings, MissingRequiredKeyNamesTheSection) {
  const Settings root = Settings::load_string(kYaml, "case.yaml");
  const std::string message = error_of([&] { root.child("settings").required<double>("end"); });
  EXPECT_NE(message.find("case.yaml:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("missing required key 'settings.end'"), std::string::npos) << message;
}

TEST(Settings, OutOfRangeValue) {
  const Settings root = Settings::load_string(kYaml, "case.yaml");
  const std::string message = error_of(
      [&] { root.child("settings").required_in_range("delta_t", cocopp::Range::at_least(0.01)); });
  EXPECT_NE(message.find("case.yaml:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("must be >= 0.01"), std::string::npos) << message;
}

TEST(Settings, UnknownKeySuggestsTheNearestValidOne) {
  const Settings root =
      Settings::load_string("settings:\n  delta_t: 1\n  number_of_timestep: 3\n", "case.yaml");
  const Settings run = root.child("settings");
  run.required<double>("delta_t");
  run.get<int>("number_of_timesteps", 1);
  const std::string message = error_of([&] { root.check_unused_keys(); });
  EXPECT_NE(message.find("case.yaml:3:3: unknown key 'settings.number_of_timestep'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'number_of_timesteps'?"), std::string::npos) << message;
}

TEST(Settings, UnreadSectionIsUnknown) {
  const Settings root = Settings::load_string("settings: {}\nextra: {a: 1}\n", "case.yaml");
  root.child("settings");
  EXPECT_NE(error_of([&] { root.check_unused_keys(); }).find("unknown key 'extra'"),
            std::string::npos);
}

TEST(Settings, ChoiceSuggestsNearest) {
  const Settings root = Settings::load_string("transport: pipes\n", "c.yaml");
  const std::string message = error_of([&] {
    root.get_choice("transport", "pipe", {"pipe", "file"});
  });
  EXPECT_NE(message.find("did you mean 'pipe'?"), std::string::npos) << message;
}

TEST(Settings, JsonIsReadWithLineNumbers) {
  const Settings root =
      Settings::load_string("{\n  \"settings\": {\n    \"delta_t\": \"x\"\n  }\n}\n", "case.json");
  EXPECT_EQ(root.child("settings").path(), "settings");
  const std::string message = error_of([&] { root.child("settings").required<double>("delta_t"); });
  EXPECT_NE(message.find("case.json:3:"), std::string::npos) << message;
}

TEST(Settings, SyntaxErrorNamesTheLine) {
  const std::string message =
      error_of([] { Settings::load_string("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_NE(message.find("bad.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
}

// Issue 17, defect 8: input the parser accepts but would ignore silently.
TEST(Settings, AKeyGivenTwiceIsAnErrorAtItsSecondLine) {
  const std::string message = error_of([] {
    Settings::load_string("settings:\n  delta_t: 1\n  number_of_timesteps: 2\n  delta_t: 3\n",
                          "twice.yaml");
  });
  EXPECT_NE(message.find("twice.yaml:4:3: key 'delta_t' in 'settings' is given twice (first at "
                         "line 2)"),
            std::string::npos)
      << message;
  const std::string in_list =
      error_of([] { Settings::load_string("{\"a\": [{\"b\": 1, \"b\": 2}]}", "twice.json"); });
  EXPECT_NE(in_list.find("key 'b' in 'a[0]' is given twice"), std::string::npos) << in_list;
}

TEST(Settings, ContentAfterTheDocumentIsAnError) {
  const std::string second = error_of([] { Settings::load_string("a: 1\n---\nb: 2\n", "c.yaml"); });
  EXPECT_NE(second.find("c.yaml:2:1: content after the end of the case"), std::string::npos)
      << second;
  const std::string after_json =
      error_of([] { Settings::load_string("{\"a\": 1}\n{\"b\": 2}\n", "c.json"); });
  EXPECT_NE(after_json.find("c.json:2:1: content after the end of the case"), std::string::npos)
      << after_json;
}

TEST(Settings, AKeyThatIsNotANameIsAnErrorWithItsLine) {
  const std::string message =
      error_of([] { Settings::load_string("a:\n  ? [1, 2]\n  : 3\n", "c.yaml"); });
  EXPECT_NE(message.find("c.yaml:2:5: a key in 'a' is a list or a mapping"), std::string::npos)
      << message;
}

// Issue 17, defect 10: a name that becomes part of file names must not be a path.
TEST(Settings, NamesThatWouldBePathsAreRejected) {
  const Settings root =
      Settings::load_string("a: flow-1.x\nb: ../../x\nc: .hidden\nd: 'with space'\n", "c.yaml");
  EXPECT_EQ(root.get_name("a", "z"), "flow-1.x");
  EXPECT_EQ(root.get_name("missing", "structure"), "structure");
  for (const char* key : {"b", "c", "d"})
    EXPECT_NE(error_of([&] { root.get_name(key, "z"); }).find("is not a plain name"),
              std::string::npos)
        << key;
  EXPECT_NE(error_of([&] { root.get_name("b", "z"); }).find("c.yaml:2:4: 'b': '../../x'"),
            std::string::npos)
      << error_of([&] { root.get_name("b", "z"); });
}

TEST(Settings, NonFiniteNumbersAreRejected) {
  const Settings root = Settings::load_string("omega: .nan\n", "c.yaml");
  EXPECT_NE(error_of([&] { root.required<double>("omega"); }).find("finite"), std::string::npos);
}

TEST(Suggest, EditDistanceAndSuggestion) {
  EXPECT_EQ(cocopp::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(cocopp::did_you_mean("gaus_seidel", {"gauss_seidel", "iqni"}),
            "; did you mean 'gauss_seidel'?");
  EXPECT_EQ(cocopp::did_you_mean("zzzzzz", {"gauss_seidel", "iqni"}), "");
}

// Issue 17, defect 9: yaml-cpp stops at 500 levels with "syntax error: bad file".
TEST(Settings, NestingTooDeepIsNamedAsSuch) {
  const std::string deep = "settings: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  const std::string message = error_of([&] { Settings::load_string(deep, "deep.yaml"); });
  EXPECT_NE(message.find("deep.yaml:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("nested more than 500 deep"), std::string::npos) << message;
  EXPECT_EQ(message.find("bad file"), std::string::npos) << message;
}

// The key registry finds a mapping's entry by its path (it scanned all entries, which made
// `check` quadratic in the length of a list: 22 s for 80k entries; bench/case_check_scaling.py
// measures it). Entries must still be told apart: a list's items, and the empty mappings of
// absent keys, each keep their own known keys.
TEST(Settings, EachItemOfALongListKeepsItsOwnKnownKeys) {
  std::string text = "items:\n";
  for (int i = 0; i < 2000; ++i) text += "  - {name: n" + std::to_string(i) + "}\n";
  text += "  - {name: last, nmae: typo}\n";
  const Settings root = Settings::load_string(text, "list.yaml");
  for (const Settings& item : root.list("items")) (void)item.required<std::string>("name");
  // Copies of a Settings share its entry; a second child_or_empty of an absent key as well.
  (void)root.child_or_empty("absent").get<double>("a", 1.0);
  (void)root.child_or_empty("absent").get<double>("b", 1.0);
  const std::string message = error_of([&] { root.check_unused_keys(); });
  EXPECT_NE(message.find("list.yaml:2002:18: unknown key 'items[2000].nmae'; did you mean 'name'"),
            std::string::npos)
      << message;
}

// Found by the case-file fuzz target (tests/fuzz): a NUL byte made yaml-cpp's LoadAll collect
// empty documents for ever ('cocopp check' hung, eating memory). Control characters are an
// error at their line, and at most two documents are read.
TEST(Settings, AControlCharacterIsAnErrorAtItsPosition) {
  const std::string text = std::string("settings:\n  delta_t: 1\n  a") + '\0' + "b: 2\n";
  const std::string message = error_of([&] { Settings::load_string(text, "nul.yaml"); });
  EXPECT_NE(message.find("nul.yaml:3:4: a control character (byte 0x00): a case file is text"),
            std::string::npos)
      << message;
  EXPECT_NE(error_of([] {
              Settings::load_string("a: \x1b[31m\n", "esc.yaml");
            }).find("esc.yaml:1:4: a control character (byte 0x1b)"),
            std::string::npos);
  // Tabs and Windows line ends are text.
  EXPECT_EQ(Settings::load_string("a:\t1\r\nb: 2\r\n", "crlf.yaml").get<int>("b", 0), 2);
}

// Issue 18: a misspelt required key was reported as missing without a word about the typo
// beside it. The unread keys of the mapping are searched for a near one.
TEST(Settings, AMissingRequiredKeyPointsAtItsMisspelling) {
  const Settings root = Settings::load_string(
      "coupled_solvers:\n  type: iqni\nsolver:\n  workingdirectory: flow\n  name: a\n", "t.yaml");
  EXPECT_NE(error_of([&] { root.child("coupled_solver"); })
                .find("missing required section 'coupled_solver'; is 'coupled_solvers' (line 1) "
                      "a misspelling of it?"),
            std::string::npos);
  const Settings solver = root.child("solver");
  (void)solver.required<std::string>("name");
  EXPECT_NE(error_of([&] {
              solver.required<std::string>("working_directory");
            }).find("is 'workingdirectory' (line 4) a misspelling of it?"),
            std::string::npos);
  // A key already read, or one far from the missing key, is no hint.
  EXPECT_EQ(error_of([&] { solver.required<std::string>("nme"); }).find("misspelling"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { solver.required<double>("omega"); }).find("misspelling"),
            std::string::npos);
}

// A case file is read whole before it is parsed: a device, a directory or a huge file is
// refused first (`cocopp check /dev/zero` once grew to gigabytes).
TEST(Settings, OnlyARegularFileOfReasonableSizeIsRead) {
  EXPECT_NE(error_of([] {
              Settings::load_file("/dev/zero");
            }).find("/dev/zero: not a regular file (a device or a pipe)"),
            std::string::npos);
  EXPECT_NE(error_of([] { Settings::load_file("/tmp"); }).find("not a regular file (a directory)"),
            std::string::npos);
  const std::filesystem::path big =
      std::filesystem::temp_directory_path() / "cocopp_test_big_case.yaml";
  {
    std::ofstream out(big);
    out << "settings: {delta_t: 0.001}\n";
  }
  std::filesystem::resize_file(big, Settings::kMaxCaseFileBytes + 1);  // sparse: no disk used
  EXPECT_NE(error_of([&] { Settings::load_file(big); }).find("larger than the 16 MiB"),
            std::string::npos);
  std::filesystem::resize_file(big, 27);
  EXPECT_EQ(Settings::load_file(big).child("settings").required<double>("delta_t"), 0.001);
  std::filesystem::remove(big);
}

// Issue 51: the slips of a hand-written case file, said in words at their line.
TEST(SyntaxSlips, ATabInTheIndentationIsNamedAtItsColumn) {
  const std::string message =
      loading_error("settings:\n  delta_t: 1\n\tnumber_of_timesteps: 2\n", "t.yaml");
  EXPECT_NE(message.find("t.yaml:3:1: a tab character in the indentation of line 3: YAML indents "
                         "with spaces only"),
            std::string::npos)
      << message;
}

TEST(SyntaxSlips, ALineIndentedMoreThanAKeyWithAValueNamesBothLines) {
  const std::string message =
      loading_error("coupled_solver:\n  type: iqni\n    omega: 0.05\n", "i.yaml");
  EXPECT_NE(message.find("i.yaml:3:5: line 3 is indented more (4 spaces) than line 2 above it (2 "
                         "spaces), whose key already has its value ('type: iqni')"),
            std::string::npos)
      << message;
}

TEST(SyntaxSlips, ALineIndentedToNoMappingNamesTheColumnsItCouldTake) {
  const std::string message =
      loading_error("coupled_solver:\n  type: iqni\n # a comment\n omega: 0.05\n", "d.yaml");
  EXPECT_NE(message.find("d.yaml:4:2: line 4 is indented by 1 space, which lines it up with none "
                         "of the mappings above it (their keys start in columns 1, 3)"),
            std::string::npos)
      << message;
}

TEST(SyntaxSlips, TopLevelKeysIndentedUnlikeTheFirstArePointedAt) {
  // The first key indented: YAML ends the document at the next key in column 1.
  const std::string message =
      loading_error("  settings:\n  delta_t: 1\ncoupled_solver:\n  type: iqni\n", "s.yaml");
  EXPECT_NE(message.find("s.yaml:3:1: line 3 starts further left (column 1) than the file's first "
                         "key (line 1, column 3)"),
            std::string::npos)
      << message;
}

TEST(SyntaxSlips, ListsFlowValuesAndBlockScalarsAreNotSlips) {
  // A syntax error of another kind after well-indented lists, flow values and a block scalar
  // keeps yaml-cpp's own words.
  const std::string lists =
      "solver_wrappers:\n  - type: a\n    name: b\n    flags: {x: 1, y: [1, 2]}\n"
      "  - type: c\n    text: |\n      free\n        text\n    name: d\ncriteria:\n- a: 1\n"
      "  b: 2\n";
  const std::string message = loading_error(lists + "last: [1, 2\n", "ok.yaml");
  EXPECT_NE(message.find("ok.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
  // The same text without the slip at its end is a case.
  EXPECT_NO_THROW(Settings::load_string(lists, "ok.yaml"));
}

TEST(SyntaxSlips, JsonIsStrict) {
  const auto error = [](const std::string& text) { return loading_error(text, "c.json"); };
  const std::string trailing = error("{\n  \"a\": 1,\n  \"b\": 2,\n}\n");
  EXPECT_NE(trailing.find("c.json:3:9: a comma before the closing '}' at 4:1: JSON allows no "
                          "trailing comma"),
            std::string::npos)
      << trailing;
  const std::string missing = error("{\"a\": {\"b\": 1 \"c\": 2}}");
  EXPECT_NE(missing.find("c.json:1:14: a comma is missing after 1:13 (before \"c\" at 1:15)"),
            std::string::npos)
      << missing;
  const std::string comment = error("{\n  // the step\n  \"a\": 1\n}\n");
  EXPECT_NE(comment.find("c.json:2:3: a comment: JSON has none"), std::string::npos) << comment;
  const std::string list = error("{\"a\": [1, 2,]}");
  EXPECT_NE(list.find("c.json:1:12: a comma before the closing ']' at 1:13"), std::string::npos)
      << list;
  // YAML's own extensions stay YAML's: the same trailing comma in a .yaml file is read.
  EXPECT_NO_THROW(Settings::load_string("{\"a\": 1, \"b\": 2,}", "c.yaml"));
}

TEST(SyntaxSlips, BytesThatAreNotUtf8AreNamedAtTheirPosition) {
  const std::string message = loading_error("a: 1  # caf\xe9\nb: 2\n", "u.yaml");
  EXPECT_NE(message.find("u.yaml:1:12: a byte that is not UTF-8 (0xe9)"), std::string::npos)
      << message;
  EXPECT_NO_THROW(
      Settings::load_string("a: 1  # caf\xc3\xa9 \xe2\x86\x92 \xf0\x9f\x98\x80\n", "u.yaml"));
  // An overlong form and a surrogate are not UTF-8 either.
  EXPECT_NE(loading_error("a: \xc0\xaf\n", "u.yaml").find("not UTF-8"), std::string::npos);
  EXPECT_NE(loading_error("a: \xed\xa0\x80\n", "u.yaml").find("not UTF-8"), std::string::npos);
}

TEST(SyntaxSlips, ANullKeyIsCalledSo) {
  const std::string message = loading_error("coupled_solver:\n  ~: 0.05\n", "n.yaml");
  EXPECT_NE(message.find("n.yaml:2:3: a key in 'coupled_solver' is empty or null"),
            std::string::npos)
      << message;
}
