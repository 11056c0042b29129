#include "crankcheck/validation/report_document.h"

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm.h>

#include <algorithm>
#include <cctype>
#include <string_view>
#include <cstdlib>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "crankcheck/validation/engines.h"
#include "crankcheck/validation/errors.h"
#include "crankcheck/validation/install_paths.h"
#include "crankcheck/validation/process.h"
#include "crankcheck/validation/table.h"
#include "flywheel_run.h"

namespace crankcheck::validation {
namespace fs = std::filesystem;

namespace {

std::string escapeCell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out;
}

std::string escapeHtml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// cmark-gfm with GitHub's table extension: Markdown to an HTML fragment. Raw HTML in the Markdown is not passed
// through (CMARK_OPT_DEFAULT is safe): the report's text comes from data, some of it the user's. No autolink extension:
// the report writes its links as links, and a scene named "www.example.com" or "a@example.com" is text.
std::string renderMarkdown(const std::string& markdown) {
  cmark_gfm_core_extensions_ensure_registered();
  std::unique_ptr<cmark_parser, void (*)(cmark_parser*)> parser(cmark_parser_new(CMARK_OPT_DEFAULT), cmark_parser_free);
  if (!parser) throw std::runtime_error("cmark-gfm: cannot create a parser");
  for (const char* name : {"table"})
    if (cmark_syntax_extension* extension = cmark_find_syntax_extension(name))
      cmark_parser_attach_syntax_extension(parser.get(), extension);
  cmark_parser_feed(parser.get(), markdown.data(), markdown.size());
  std::unique_ptr<cmark_node, void (*)(cmark_node*)> document(cmark_parser_finish(parser.get()), cmark_node_free);
  if (!document) throw std::runtime_error("cmark-gfm: cannot parse the report's Markdown");
  char* html = cmark_render_html(document.get(), CMARK_OPT_DEFAULT, cmark_parser_get_syntax_extensions(parser.get()));
  std::string out(html);
  std::free(html);
  return out;
}

bool isWordCharacter(char c) { return std::isalnum(static_cast<unsigned char>(c)) || static_cast<unsigned char>(c) >= 0x80; }

}  // namespace

std::string escapeMarkdownText(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '\r') {
      out += ' ';
      continue;
    }
    // '_' opens emphasis only beside a non-word character (GitHub's rule for intraword underscores).
    const bool opens = c == '_' ? !(i > 0 && isWordCharacter(text[i - 1]) && i + 1 < text.size() && isWordCharacter(text[i + 1]))
                                : std::string_view("\\`*[]<>&!#~").find(c) != std::string_view::npos;
    if (opens) out += '\\';
    out += c;
  }
  return out;
}

std::string formatCodeSpan(const std::string& text) {
  size_t longest = 0;
  for (size_t i = 0; i < text.size();) {
    size_t run = 0;
    while (i + run < text.size() && text[i + run] == '`') ++run;
    longest = std::max(longest, run);
    i += std::max<size_t>(run, 1);
  }
  const std::string fence(longest + 1, '`');
  std::string body;
  for (const char c : text) body += (c == '\n' || c == '\r') ? ' ' : c;
  const bool pad = !body.empty() && (body.front() == '`' || body.back() == '`');
  return fence + (pad ? " " : "") + body + (pad ? " " : "") + fence;
}

std::vector<std::string> listSceneNames(const TableSet& tables) {
  std::set<std::string> names;
  for (const auto& [name, table] : tables)
    for (size_t c = 0; c < table.columns().size(); ++c) {
      const Column& column = table.columns()[c];
      if (!column.text || (column.name != "scene" && column.name != "family")) continue;
      for (size_t r = 0; r < table.size(); ++r) {
        const Cell cell = table.cell(r, c);
        if (const std::string* text = std::get_if<std::string>(&cell)) names.insert(*text);
      }
    }
  return {names.begin(), names.end()};
}

ReportDocument::ReportDocument(std::string title) : title_(std::move(title)) { body_ = "# " + title_ + "\n\n"; }

void ReportDocument::addHeading(int level, const std::string& text, const std::string& id) {
  // One line, as a heading must be (a scene named "two\nlines" split into a heading "two" and a paragraph "lines"),
  // and plain text: a heading is words, never Markdown (a scene named "[link](javascript:...)" made a live link of its
  // own section's heading).
  const std::string line = escapeMarkdownText(text);
  body_ += std::string(static_cast<size_t>(level), '#') + " " + line + "\n\n";
  std::string anchor = id;
  if (anchor.empty())
    for (const char c : text) {
      if (std::isalnum(static_cast<unsigned char>(c))) anchor += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      else if ((c == ' ' || c == '-') && !anchor.empty() && anchor.back() != '-') anchor += '-';
    }
  while (!anchor.empty() && anchor.back() == '-') anchor.pop_back();
  if (anchor.empty()) anchor = "section";
  const std::string base = anchor;
  for (int n = 2; std::any_of(headings_.begin(), headings_.end(), [&](const Heading& h) { return h.id == anchor; }); ++n)
    anchor = base + "-" + std::to_string(n);
  headings_.push_back({level, text, anchor});
}

void ReportDocument::showAsWritten(std::vector<std::string> texts) {
  as_written_.clear();
  for (std::string& t : texts) {
    std::string escaped = escapeMarkdownText(t);
    if (!t.empty() && escaped != t) as_written_.emplace_back(std::move(t), std::move(escaped));
  }
  // The longest first: a scene "a*b*c" is escaped whole, not as "a*b" and the rest.
  std::sort(as_written_.begin(), as_written_.end(), [](const auto& a, const auto& b) {
    return a.first.size() != b.first.size() ? a.first.size() > b.first.size() : a.first < b.first;
  });
  as_written_.erase(std::unique(as_written_.begin(), as_written_.end()), as_written_.end());
}

std::string ReportDocument::escapeOutsideTexts(const std::string& markdown) const {
  if (as_written_.empty()) return markdown;
  std::string out;
  for (size_t i = 0; i < markdown.size();) {
    const char c = markdown[i];
    const auto match = std::find_if(as_written_.begin(), as_written_.end(),
                                    [&](const auto& t) { return markdown.compare(i, t.first.size(), t.first) == 0; });
    if (match != as_written_.end()) {
      out += match->second;
      i += match->first.size();
      continue;
    }
    if (c == '\\' && i + 1 < markdown.size()) {  // an escape already made: as it is
      out.append(markdown, i, 2);
      i += 2;
      continue;
    }
    if (c == '`') {  // a code span (a run of n backticks to the next run of exactly n) as it is; a lone run is text
      size_t run = 0;
      while (i + run < markdown.size() && markdown[i + run] == '`') ++run;
      size_t end = std::string::npos;
      for (size_t j = i + run; j < markdown.size();) {
        if (markdown[j] != '`') {
          ++j;
          continue;
        }
        size_t other = 0;
        while (j + other < markdown.size() && markdown[j + other] == '`') ++other;
        if (other == run) {
          end = j + other;
          break;
        }
        j += other;
      }
      const size_t stop = end == std::string::npos ? i + run : end;
      out.append(markdown, i, stop - i);
      i = stop;
      continue;
    }
    out += c;
    ++i;
  }
  return out;
}

void ReportDocument::addParagraph(const std::string& markdown) { body_ += escapeOutsideTexts(markdown) + "\n\n"; }

void ReportDocument::addTable(const std::vector<std::string>& columns, const std::vector<std::vector<std::string>>& rows) {
  std::string line = "|", rule = "|";
  for (const std::string& c : columns) {
    line += " " + escapeCell(escapeOutsideTexts(c)) + " |";
    rule += "---|";
  }
  body_ += line + "\n" + rule + "\n";
  for (const auto& row : rows) {
    line = "|";
    for (size_t i = 0; i < columns.size(); ++i) line += " " + escapeCell(i < row.size() ? escapeOutsideTexts(row[i]) : std::string()) + " |";
    body_ += line + "\n";
  }
  body_ += "\n";
}

void ReportDocument::addFigure(const std::string& name, const std::string& written_caption) {
  const std::string caption = escapeOutsideTexts(written_caption);
  body_ += "[![" + escapeCell(caption) + "](" + name + ".png)](" + name + ".svg)\n\n*" + caption + "* ([SVG](" + name +
           ".svg), [CSV](data/" + name + ".csv))\n\n";
}

std::string ReportDocument::toMarkdown() const { return body_; }

std::string ReportDocument::toHtml() const {
  std::string fragment = renderMarkdown(body_);
  // Cells that start with a mark of kCellMarks: coloured by their class instead.
  for (size_t i = 0; i < std::size(kCellMarks); ++i) {
    const std::string from = std::string("<td>") + kCellMarks[i] + " ", to = "<td class=\"mark" + std::to_string(i) + "\">";
    for (size_t at = fragment.find(from); at != std::string::npos; at = fragment.find(from, at + to.size()))
      fragment.replace(at, from.size(), to);
  }
  // A wide table scrolls in its own box, never the page (at 1200 px the scenes table is wider than the text).
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"<table>", "<div class=\"scroll\"><table>"},
                                 {"</table>", "</table></div>"}})
    for (size_t at = fragment.find(from); at != std::string::npos; at = fragment.find(from, at + to.size()))
      fragment.replace(at, from.size(), to);
  // Anchors on every heading (stable: a part's key, or made of the heading's text), in order; the level-2 and level-3
  // ones make the table of contents (a scene section's topics, level 4, would push the sections off the first screens).
  std::string toc = "<nav><h2>Contents</h2><ul>\n";
  size_t search = 0;
  for (const Heading& heading : headings_) {
    const std::string tag = "<h" + std::to_string(heading.level) + ">";
    const size_t at = fragment.find(tag, search);
    if (at == std::string::npos) break;
    fragment.insert(at + tag.size() - 1, " id=\"" + escapeHtml(heading.id) + "\"");
    search = at + tag.size();
    if (heading.level > 3) continue;
    toc += std::string(heading.level == 3 ? "<li class=\"sub\">" : "<li>") + "<a href=\"#" + escapeHtml(heading.id) +
           "\">" + escapeHtml(heading.text) + "</a></li>\n";
  }
  toc += "</ul></nav>\n";
  // The title and the first section (a report's verdict) stay first, on the first screen; the contents follow them.
  const size_t first_section = fragment.find("<h2");
  const size_t second_section = first_section == std::string::npos ? first_section : fragment.find("<h2", first_section + 3);
  const size_t title_end = fragment.find("</h1>");
  if (second_section != std::string::npos) fragment.insert(second_section, toc + "\n");
  else if (title_end != std::string::npos) fragment.insert(title_end + 5, "\n" + toc);
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escapeHtml(title_) +
         "</title>\n<style>\nbody{font-family:sans-serif;max-width:72em;margin:2em auto;padding:0 1em;line-height:1.4}\n"
         "table{border-collapse:collapse;margin:1em 0;line-height:1.2}td,th{border:1px solid #bbb;padding:.15em .5em}\n"
         "img{max-width:100%}code{background:#f4f4f4}nav li.sub{margin-left:1.5em}nav>ul{columns:3 18em}\n"
         "div.scroll{overflow-x:auto;max-width:100%;margin:1em 0}div.scroll>table{margin:0}pre{overflow-x:auto}\n"
         "td.mark0{background:#c6efc6}td.mark1{background:#fff2a8}td.mark2{background:#ffd29e}"
         "td.mark3{background:#ff9e9e;font-weight:bold}\n</style>\n</head>\n<body>\n" +
         fragment + "</body>\n</html>\n";
}

namespace {

// Every figure script reads its data from data/ and writes into the report's folder (gnuplot runs there); a script
// that draws one engine's values beside the closed forms draws the first reference engine in play (`reference`, its
// library's name `reference_title`) and the run of the first engine whose free run takes loads (`loaded_run`, empty
// when none is in play): the engines a SatOutScope leaves (engines.h). Engine names are the registry's, never a user's.
std::string formatFigureVariables() {
  const std::vector<const Engine*> loaded = listLoadedRunEngines();
  return "in_dir='data'; out_dir='.'; reference='" + listReferenceEngines().front()->name + "'; reference_title='" +
         getReferenceName() + "'; loaded_run='" + (loaded.empty() ? "" : loaded.front()->name) + "'";
}

// reports/NAME.gp, absolute. @throws EnvironmentError if it is not there.
fs::path findFigureScript(const std::string& name) {
  const fs::path script = fs::absolute(findReportsDir() / (name + ".gp"));
  if (!fs::is_regular_file(script)) throw EnvironmentError("gnuplot script not found: " + quotePath(script));
  return script;
}

// Both of figure NAME's files are in `dir`.
bool isDrawn(const fs::path& dir, const std::string& name) {
  return fs::exists(dir / (name + ".svg")) && fs::exists(dir / (name + ".png"));
}

}  // namespace

void drawFigure(const std::string& name, const fs::path& dir, const std::string& definitions) {
  const fs::path script = findFigureScript(name);
  ProgramCall call{{"gnuplot", "-e", formatFigureVariables() + "; " + definitions, script.string()}, dir};
  call.timeout_seconds = kGnuplotFigureSeconds;
  const ProgramResult r = runProgram(call);
  if (r.timed_out)
    throw EnvironmentError("gnuplot: " + quotePath(script) + ": no figure within " + std::to_string(static_cast<int>(kGnuplotFigureSeconds)) +
                           " s; gnuplot was ended");
  if (r.exit_status != 0 || !isDrawn(dir, name))
    throw EnvironmentError("gnuplot failed on " + quotePath(script) + ":\n" + r.out + r.err);
}

bool drawFigures(const std::vector<std::string>& names, const fs::path& dir) {
  if (names.size() > 1) {
    ProgramCall call{{"gnuplot"}, dir};
    // "reset session" on its own: gnuplot 5.4 refuses more on its line. It keeps `set datafile columnheaders` (the
    // scripts read columns by header name), so each script also starts with the header mode off, as when alone.
    const std::string variables = formatFigureVariables();
    for (const std::string& name : names)
      call.argv.insert(call.argv.end(), {"-e", "reset session", "-e", "unset datafile columnheaders", "-e",
                                         variables, findFigureScript(name).string()});
    call.timeout_seconds = kGnuplotFigureSeconds * static_cast<double>(names.size());
    const ProgramResult r = runProgram(call);
    if (r.timed_out) {  // not drawn again: a gnuplot that hangs would hang again, a figure at a time
      std::string scripts;
      for (const std::string& name : names) scripts += (scripts.empty() ? "" : ", ") + name + ".gp";
      throw EnvironmentError("gnuplot: " + quotePath(findReportsDir()) + ": no figures within " +
                             std::to_string(static_cast<int>(call.timeout_seconds)) + " s for " + scripts +
                             "; gnuplot was ended");
    }
    if (r.exit_status == 0 &&
        std::all_of(names.begin(), names.end(), [&](const std::string& name) { return isDrawn(dir, name); }))
      return true;
  }
  for (const std::string& name : names) drawFigure(name, dir);
  return names.size() <= 1;
}

}  // namespace crankcheck::validation
