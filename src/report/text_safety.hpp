#pragma once
// Text from input files (titles, file names, values quoted in errors) travels into
// terminals, spreadsheets, links and folder names. Each of these reads some characters
// as commands; these functions make such text inert where it lands.
#include <string>
#include <string_view>

namespace j232::report {

// Control characters (escape sequences among them) replaced by '?', so a title cannot
// move the cursor, recolour or retitle a terminal.
std::string terminal_safe(std::string_view text);

// A CSV cell that a spreadsheet will show as text: quoted when needed, and a leading
// '=', '+', '-', '@', tab or carriage return (a formula to Excel, LibreOffice, Sheets)
// prefixed with an apostrophe.
std::string csv_text_cell(std::string_view text);

// A relative URL path ("./name/report.html") with every byte outside the unreserved set
// percent-encoded, so no scheme ("javascript:") or query can be smuggled in.
std::string relative_url(std::string_view path);

// JSON text to sit inside an HTML <script> block: every '<', '>' and '&' (which can occur only
// inside JSON strings) written as its \u escape, so no name a user gave ("</script>", "<!--",
// "]]>") can close the block or change how the page parses it; JSON.parse reads it unchanged.
std::string script_safe_json(std::string_view json);

// A folder name derived from a file name: letters, digits, '-', '_' and '.' only, no
// leading dot (so never "." or ".."), at most 100 characters, never empty.
std::string safe_folder_name(std::string_view stem);

}  // namespace j232::report
