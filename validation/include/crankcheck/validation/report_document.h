#pragma once
/// @file
/// A report page: Markdown (index.md, as written) and the same page as HTML (index.html), rendered from that
/// Markdown by cmark-gfm (GitHub's tables), with a table of contents, `lang`, a title and inline style: it works
/// offline, opened from the folder.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "crankcheck/validation/table.h"

namespace crankcheck::validation {

/// Marks that colour a table cell from pass to fail (green, yellow, orange, red) when the cell starts with one and a
/// space: in Markdown the mark itself, in HTML the cell's background (the mark is dropped there, so no emoji font
/// is needed).
inline constexpr const char* kCellMarks[4] = {"\U0001F7E9", "\U0001F7E8", "\U0001F7E7", "\U0001F7E5"};

/// `text` (a scene's name: text from outside) as Markdown that shows it as written: the characters that would open a
/// link, an image, HTML, an entity, code or emphasis are backslash-escaped (an underscore only where it could open
/// emphasis: v8_cross_plane stays as it is). A newline or a carriage return becomes a space (one line).
std::string escapeMarkdownText(const std::string& text);

/// `text` as one Markdown code span that shows it as written: delimited by a run of backticks longer than any inside it
/// (a scene named "a`b" in a command to copy), padded with a space where it starts or ends with a backtick.
std::string formatCodeSpan(const std::string& text);

/// The scenes' names in `tables`: every text cell of a column named "scene" or "family" (a scene's name is its file's
/// stem, the user's), for ReportDocument::showAsWritten.
std::vector<std::string> listSceneNames(const TableSet& tables);

class ReportDocument {
 public:
  explicit ReportDocument(std::string title);

  /// Texts from outside the report (the scenes' names) to show as written wherever they appear in a paragraph, a cell
  /// or a caption added after this call: each occurrence outside a code span is written by escapeMarkdownText (a scene
  /// named "[x](javascript:...)" was a live link in index.md's tables and sentences). Inside a code span the text is
  /// shown as written already: the parts put names there with formatCodeSpan.
  void showAsWritten(std::vector<std::string> texts);

  /// A heading (level 2 or 3 go into the table of contents; the title is level 1). `id`: its anchor in the HTML page
  /// (a part's key: `#torsion` names the torsion part in every report); empty: one made of the text (lower case, letters,
  /// digits and '-'), made unique with "-2", "-3", ...
  void addHeading(int level, const std::string& text, const std::string& id = {});
  /// A paragraph of Markdown (inline code, emphasis, links).
  void addParagraph(const std::string& markdown);
  /// A table; every cell is escaped (a '|' or a newline in a cell cannot break the table).
  void addTable(const std::vector<std::string>& columns, const std::vector<std::vector<std::string>>& rows);
  /// The figure NAME.png (a link to NAME.svg) with its caption and a link to data/NAME.csv.
  void addFigure(const std::string& name, const std::string& caption);

  std::string toMarkdown() const;
  /// The Markdown rendered by cmark-gfm inside a complete HTML page. @throws std::runtime_error if cmark-gfm fails.
  std::string toHtml() const;

 private:
  /// `markdown` with every text of showAsWritten escaped outside code spans.
  std::string escapeOutsideTexts(const std::string& markdown) const;

  std::string title_;
  std::string body_;
  std::vector<std::pair<std::string, std::string>> as_written_;  ///< (text, escaped), the longest text first
  struct Heading {
    int level;
    std::string text, id;
  };
  std::vector<Heading> headings_;
};

/// [s] How long gnuplot may take to draw one figure: the largest takes under a second; two minutes leave room for a
/// loaded machine and still end a gnuplot that hangs.
constexpr double kGnuplotFigureSeconds = 120.0;

/// Draws figure NAME: runs gnuplot on reports/NAME.gp (findReportsDir) in `dir` without a shell; the script reads
/// data/NAME.csv and writes NAME.svg and NAME.png. `definitions` are extra gnuplot -e assignments made by the caller
/// from its own fixed names (never from user input).
/// @throws EnvironmentError if the script is missing, gnuplot fails, or it has not finished within
/// kGnuplotFigureSeconds (then it is ended).
void drawFigure(const std::string& name, const std::filesystem::path& dir, const std::string& definitions = "");

/// Draws the figures `names` (drawFigure's, without definitions) by one gnuplot, one script after the other, each after
/// `reset session` (no setting or variable of one script reaches the next: on a report's data the PNGs are
/// drawFigure's byte for byte, the SVGs differ at most in the stroke attribute of an empty group). One process saves
/// gnuplot's start and its cairo and fonts set-up for every figure (bench/README.md, "One gnuplot for several
/// figures"). Where a script fails (its error, a missing file), every figure of `names` is drawn again on
/// its own by drawFigure, whose error names the failing script.
/// @throws EnvironmentError as drawFigure (a missing script before gnuplot starts); when gnuplot has not finished within kGnuplotFigureSeconds a figure (then
/// it is ended, and nothing is drawn again).
/// @return true when one gnuplot drew them all; false when they were drawn again one by one (every figure drawn, at
///         twice the cost: a script failed, or one left a setting behind that broke the next).
bool drawFigures(const std::vector<std::string>& names, const std::filesystem::path& dir);

}  // namespace crankcheck::validation
