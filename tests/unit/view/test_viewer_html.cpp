// The HTML page writer (issue #25, include/interfere/view/html.h): placeholders filled, the data
// unable to end its <script> element, the title escaped, the page without a template an error.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "interfere/view/html.h"
#include "interfere/view/json.h"

namespace interfere::view {
namespace {

const std::string kTemplate =
    "<!doctype html><html><head><title>INTERFERE_VIEWER_TITLE</title></head><body>"
    "<script id=\"interfere-data\" type=\"application/json\">/*INTERFERE_VIEWER_DATA*/</script>"
    "<script>/* the viewer */</script></body></html>";

Document doc_with_names(const std::string& body_name, const std::string& title) {
  Document d;
  d.title = title;
  ViewMesh m;
  m.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.mesh.triangles = {{0, 1, 2}};
  d.meshes.push_back(m);
  ViewBody b;
  b.id = "b1";
  b.name = body_name;
  d.bodies.push_back(b);
  return d;
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

/// The text of the data <script> element (what the page's JSON.parse reads).
std::string data_element(const std::string& page) {
  const std::string open = "<script id=\"interfere-data\" type=\"application/json\">";
  const std::size_t a = page.find(open);
  if (a == std::string::npos) return "";
  const std::size_t b = page.find("</script>", a);  // the HTML parser ends the element at the first "</script>"
  return page.substr(a + open.size(), b - a - open.size());
}

TEST(ViewerHtml, ScriptEndInANameCannotEndTheDataElement) {
  const std::string evil = "bolt </script><script>alert(1)</script> <!-- <script> end";
  const Expected<std::string> page = html_page(doc_with_names(evil, "t"), kTemplate);
  ASSERT_TRUE(page) << page.error().message();
  EXPECT_EQ(count(*page, "</script>"), 2u);  // the template's two
  EXPECT_EQ(count(*page, "<!--"), 0u);
  const std::string data = data_element(*page);
  const nlohmann::json j = nlohmann::json::parse(data);  // the whole element is the JSON
  EXPECT_EQ(j["bodies"][0]["name"], evil);
  EXPECT_EQ(j["schema"], "interfere.viewer");
  // The rest of the template is intact.
  EXPECT_NE(page->find("<script>/* the viewer */</script></body></html>"), std::string::npos);
  EXPECT_EQ(page->find("/*INTERFERE_VIEWER_DATA*/"), std::string::npos);
}

TEST(ViewerHtml, TitleIsHtmlEscaped) {
  const Expected<std::string> page = html_page(doc_with_names("x", "a < b & \"c\" 'd' </title>"), kTemplate);
  ASSERT_TRUE(page) << page.error().message();
  EXPECT_NE(page->find("<title>a &lt; b &amp; &quot;c&quot; &#39;d&#39; &lt;/title&gt;</title>"), std::string::npos)
      << *page;
  EXPECT_EQ(page->find("INTERFERE_VIEWER_TITLE"), std::string::npos);
  // Placeholder text inside the title or the data is not a placeholder.
  const Expected<std::string> again = html_page(doc_with_names("/*INTERFERE_VIEWER_DATA*/", "INTERFERE_VIEWER_TITLE"), kTemplate);
  ASSERT_TRUE(again) << again.error().message();
  EXPECT_EQ(nlohmann::json::parse(data_element(*again))["bodies"][0]["name"], "/*INTERFERE_VIEWER_DATA*/");
  EXPECT_NE(again->find("<title>INTERFERE_VIEWER_TITLE</title>"), std::string::npos);
}

TEST(ViewerHtml, WithoutTemplateOrPlaceholdersIsAnError) {
  const Document d = doc_with_names("x", "t");
  const Expected<std::string> none = html_page(d, "");
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().reason.find("no HTML viewer"), std::string::npos) << none.error().reason;
  EXPECT_NE(none.error().reason.find("INTERFERE_WITH_VIEWER=ON"), std::string::npos);
  const Expected<std::string> no_data = html_page(d, "<title>INTERFERE_VIEWER_TITLE</title>");
  ASSERT_FALSE(no_data);
  EXPECT_NE(no_data.error().reason.find("INTERFERE_VIEWER_DATA"), std::string::npos) << no_data.error().reason;
  const Expected<std::string> twice = html_page(d, kTemplate + "/*INTERFERE_VIEWER_DATA*/");
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().reason.find("2 times"), std::string::npos) << twice.error().reason;
  // The built-in template: this build has one or says why not.
  const Expected<std::string> builtin = html_page(d);
  if (has_html_viewer()) {
    ASSERT_TRUE(builtin) << builtin.error().message();
    EXPECT_EQ(nlohmann::json::parse(data_element(*builtin))["bodies"][0]["id"], "b1");
  } else {
    ASSERT_FALSE(builtin);
    EXPECT_NE(builtin.error().reason.find("no HTML viewer"), std::string::npos);
  }
}

TEST(ViewerHtml, InvalidDocumentIsAnError) {
  Document d = doc_with_names("x", "t");
  d.meshes[0].mesh.positions[0].x = std::nan("");
  const Expected<std::string> page = html_page(d, kTemplate);
  ASSERT_FALSE(page);
  EXPECT_NE(page.error().reason.find("meshes[0].positions[0]"), std::string::npos) << page.error().reason;
}

TEST(ViewerHtml, WriteHtmlWritesThePageOrNothing) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("interfere_view_html_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path out = dir / "v.html";
  const Status s = write_html(out, doc_with_names("x", "t"));
  if (has_html_viewer()) {
    ASSERT_TRUE(s) << s.error().message();
    std::ifstream in(out);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), *html_page(doc_with_names("x", "t")));
  } else {
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().file, out.string());
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // An invalid document leaves an existing file untouched.
  { std::ofstream(out) << "old"; }
  Document bad = doc_with_names("x", "t");
  bad.bodies[0].mesh = 3;
  EXPECT_FALSE(write_html(out, bad));
  std::ifstream in(out);
  std::string old;
  in >> old;
  EXPECT_EQ(old, "old");
  std::filesystem::remove_all(dir);
}

TEST(ViewerHtml, ScriptSafeJsonIsStillTheSameJson) {
  const std::string raw = nlohmann::json{{"a", "</script><!--x</"}, {"b", "\\</"}}.dump();
  const std::string safe = script_safe_json(raw);
  EXPECT_EQ(safe.find("</"), std::string::npos);
  EXPECT_EQ(safe.find("<!--"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(safe), nlohmann::json::parse(raw));
}

}  // namespace
}  // namespace interfere::view
