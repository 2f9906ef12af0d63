// pbrt-v4's Import: files parsed on other threads reach the target as the
// same calls, in the same order, as when one thread parses them in turn;
// an Import'ed file's changes to the graphics state end with it, the
// materials it names stay; errors are the first in file order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scene/pbrt/parser.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;

std::string fmt(const glm::dmat4& m) {
  char b[96];
  std::snprintf(b, sizeof b, "[%g %g %g]", m[3][0], m[3][1], m[3][2]);
  return b;
}

// Logs every call with what tells calls apart: names, material handles,
// translations, warnings.
class Log final : public pbrt::ParserTarget {
 public:
  mutable std::vector<std::string> calls;
  uint32_t materials = 0;

  void warn(const SourceLocation& w, const std::string& s) const override { calls.push_back("warn " + w.str() + " " + s); }
  void warn_line(const std::string& l) const override { calls.push_back("warn-line " + l); }
  void including(const std::string& p, size_t n) override {
    calls.push_back("including " + fs::path(p).filename().string() + " " + std::to_string(n));
  }
  void camera(const std::string& t, const pbrt::ParamSet&, const glm::dmat4&, const glm::dmat4&) override {
    calls.push_back("camera " + t);
  }
  void camera_medium(const std::string&, const SourceLocation&) override {}
  void film(const std::string& t, const pbrt::ParamSet&) override { calls.push_back("film " + t); }
  void sampler(const std::string&, const pbrt::ParamSet&) override {}
  void integrator(const std::string&, const pbrt::ParamSet&) override {}
  void pixel_filter(const std::string&, const pbrt::ParamSet&) override {}
  void begin_world(const glm::dmat4&, double, double) override { calls.push_back("world"); }
  MaterialHandle material(const std::string& t, const pbrt::ParamSet& ps,
                          const std::map<std::string, MaterialHandle>& named, const std::string&) override {
    std::string names;
    for (const auto& [n, h] : named) names += " " + n + "=" + std::to_string(h.bits);
    calls.push_back("material " + t + " at " + ps.where.str() + " named:" + names);
    return MaterialHandle::make(MaterialKind::Diffuse, ++materials);
  }
  void texture(const std::string& n, const std::string&, const std::string&, const pbrt::ParamSet&, const Mat4& m,
               const std::string&) override {
    calls.push_back("texture " + n + " " + fmt(glm::dmat4(m)));
  }
  void shape(const std::string& t, const pbrt::ParamSet& ps, const GraphicsState& gs, const std::string&) override {
    calls.push_back("shape " + t + " at " + ps.where.str() + " material " +
                    (gs.material ? std::to_string(gs.material->bits) : "none") + " " + fmt(gs.render_from_object) +
                    (gs.area_light ? " emits" : "") + (gs.reverse_orientation ? " reversed" : ""));
  }
  void light(const std::string& t, const pbrt::ParamSet&, const Mat4& m, const std::string&, const std::string&,
             const SourceLocation&) override {
    calls.push_back("light " + t + " " + fmt(glm::dmat4(m)));
  }
  void medium(const std::string& n, const pbrt::ParamSet&, const Mat4&, const std::string&) override {
    calls.push_back("medium " + n);
  }
  void begin_object(const std::string& n, const SourceLocation& w) override { calls.push_back("object " + n + " " + w.str()); }
  void end_object(const SourceLocation& w) override { calls.push_back("end object " + w.str()); }
  void object_instance(const std::string& n, const glm::dmat4& m, const glm::dmat4&, const SourceLocation& w) override {
    calls.push_back("instance " + n + " " + fmt(m) + " " + w.str());
  }
};

struct Files {
  fs::path dir;
  explicit Files(const std::string& name) : dir(fs::temp_directory_path() / ("lantern-import-" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Files() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

std::vector<std::string> parse(const std::string& path, unsigned threads) {
  Log log;
  pbrt::parse_file(path, log, threads);
  return log.calls;
}

std::string error_of(const std::string& path, unsigned threads) {
  try {
    Log log;
    pbrt::parse_file(path, log, threads);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Many placements, so that a file is handed over in several batches and
// replay overlaps parsing.
std::string placements(int n, const std::string& object) {
  std::string s;
  for (int i = 0; i < n; ++i)
    s += "AttributeBegin Translate " + std::to_string(i) + " 0 1 Rotate 30 0 1 0 ObjectInstance \"" + object +
         "\" AttributeEnd\n";
  return s;
}

TEST(Import, ParallelParsingMakesTheCallsOfParsingInTurn) {
  Files f("calls");
  f.write("a.pbrt",
          "Translate 5 0 0\nNamedMaterial \"red\"\nShape \"sphere\" \"float radius\" 2\n"
          "MakeNamedMaterial \"blue\" \"string type\" \"diffuse\"\nMaterial \"conductor\"\n"
          "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\nShape \"disk\"\nAttributeEnd\n"
          "CoordSysTransform \"nowhere\"\nTexture \"t\" \"float\" \"constant\" \"float value\" 1\n"
          "Include \"c.pbrt\"\n" + placements(30000, "thing"));
  f.write("b.pbrt", "NamedMaterial \"blue\"\nReverseOrientation\nShape \"sphere\" \"float zmin\" -1\n"
                    "ObjectBegin \"other\"\nShape \"sphere\"\nObjectEnd\nImport \"c.pbrt\"\n" +
                        placements(20000, "other") + "LightSource \"point\"\n");
  f.write("c.pbrt", "Translate 0 7 0\nShape \"cylinder\"\nMakeNamedMaterial \"red\" \"string type\" \"dielectric\"\n");
  const std::string main = f.write(
      "main.pbrt",
      "Film \"rgb\"\nCamera \"perspective\"\nWorldBegin\n"
      "MakeNamedMaterial \"red\" \"string type\" \"diffuse\"\nObjectBegin \"thing\"\nShape \"sphere\"\nObjectEnd\n"
      "Translate 0 0 3\nImport \"a.pbrt\"\nShape \"sphere\"\nImport \"b.pbrt\"\nImport \"c.pbrt\"\n"
      "NamedMaterial \"blue\"\nShape \"disk\"\nNamedMaterial \"red\"\nShape \"disk\"\n");
  const std::vector<std::string> in_turn = parse(main, 1);
  ASSERT_GT(in_turn.size(), 50000u);
  for (unsigned threads : {2u, 3u, 8u}) {
    const std::vector<std::string> parallel = parse(main, threads);
    ASSERT_EQ(parallel.size(), in_turn.size()) << threads << " threads";
    for (size_t i = 0; i < in_turn.size(); ++i) ASSERT_EQ(parallel[i], in_turn[i]) << "call " << i << ", " << threads << " threads";
  }

  // What the calls say, against pbrt-v4's Import. The Import'ed file's
  // Translate applies inside it only: its sphere is at x = 5, the main
  // file's next sphere back at the origin (z = 3 throughout).
  auto find = [&](const std::string& what) {
    for (const std::string& c : in_turn)
      if (c.find(what) != std::string::npos) return c;
    return std::string("(none: ") + what + ")";
  };
  EXPECT_NE(find("a.pbrt:3:1 material").find("[5 0 3]"), std::string::npos) << find("a.pbrt:3:1 material");
  EXPECT_NE(find("main.pbrt:10:1").find("[0 0 3]"), std::string::npos) << find("main.pbrt:10:1");
  // The main file's sphere keeps its own material (none): a's Material ended with a.
  EXPECT_NE(find("main.pbrt:10:1").find("material none"), std::string::npos) << find("main.pbrt:10:1");
  // "blue", named in a, is what b and the main file find; "red", renamed
  // by c, is c's dielectric after it.
  const std::string blue = find("material diffuse at " + (f.dir / "a.pbrt").string());
  EXPECT_NE(blue.find("red="), std::string::npos) << "a's MakeNamedMaterial sees the main file's names: " << blue;
  EXPECT_NE(find("b.pbrt:3:1").find("reversed"), std::string::npos);
  EXPECT_NE(find("main.pbrt:14:1").find("material 2"), std::string::npos) << find("main.pbrt:14:1");
  EXPECT_NE(find("main.pbrt:16:1").find("material 6"), std::string::npos) << find("main.pbrt:16:1");
  EXPECT_NE(find("unknown coordinate system").find("a.pbrt:10"), std::string::npos);
  EXPECT_NE(find("zmin").find("b.pbrt:3"), std::string::npos) << "unused parameters reported at the call: " << find("zmin");
}

TEST(Import, TheFirstErrorInFileOrderIsReported) {
  Files f("errors");
  f.write("ok.pbrt", placements(20000, "thing"));
  f.write("bad1.pbrt", placements(20000, "thing") + "Shape \"sphere\" \"float radius\" [ 1\n");
  f.write("bad2.pbrt", "Frobnicate\n");
  f.write("open.pbrt", "AttributeBegin\nShape \"sphere\"\n");
  f.write("close.pbrt", "AttributeEnd\n");
  f.write("closeobj.pbrt", "ObjectEnd\n");
  f.write("unnamed.pbrt", "\nNamedMaterial \"nope\"\n");
  f.write("self.pbrt", "Import \"self.pbrt\"\n");
  const std::string head = "Film \"rgb\"\nCamera \"perspective\"\nWorldBegin\nObjectBegin \"thing\"\nShape \"sphere\"\nObjectEnd\n";
  struct Case {
    std::string body;
    std::vector<std::string> expect;
  };
  const std::vector<Case> cases = {
      {"Import \"ok.pbrt\"\nImport \"bad1.pbrt\"\nImport \"bad2.pbrt\"\nFrobnicate\n", {"bad1.pbrt:20001", "missing ']'"}},
      {"Import \"ok.pbrt\"\nImport \"bad2.pbrt\"\nImport \"bad1.pbrt\"\n", {"bad2.pbrt:1:1", "unknown directive"}},
      {"Import \"ok.pbrt\"\nWorldBegin\nImport \"bad2.pbrt\"\n", {"main.pbrt:8:1", "only allowed before"}},
      {"Import \"open.pbrt\"\n", {"open.pbrt:1:1", "AttributeBegin without a matching AttributeEnd"}},
      {"AttributeBegin\nImport \"close.pbrt\"\nAttributeEnd\n", {"close.pbrt:1:1", "in the Import'ed file"}},
      {"ObjectBegin \"o\"\nImport \"closeobj.pbrt\"\nObjectEnd\n", {"closeobj.pbrt:1:1", "ObjectEnd without ObjectBegin"}},
      {"Import \"unnamed.pbrt\"\n", {"unnamed.pbrt:2:1", "never defined"}},
      {"Import \"self.pbrt\"\n", {"self.pbrt:1:1", "Import cycle"}},
      {"Import \"missing.pbrt\"\n", {"main.pbrt:7:1", "cannot open scene file"}},
      {"Import \"/dev/zero\"\n", {"main.pbrt:7:1", "not a regular file"}},
  };
  for (const Case& c : cases) {
    const std::string main = f.write("main.pbrt", head + c.body);
    for (unsigned threads : {1u, 2u, 4u}) {
      const std::string e = error_of(main, threads);
      for (const std::string& x : c.expect)
        EXPECT_NE(e.find(x), std::string::npos) << threads << " threads, " << c.body << ": " << e;
    }
  }
}

}  // namespace
}  // namespace lantern
