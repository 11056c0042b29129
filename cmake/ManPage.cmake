# One man page from `crankcheck [COMMAND...] --help` (the same source as --help), run at build time as
#   cmake -DCRANKCHECK=... -DCOMMAND="grade" -DVERSION=... -DOUT=.../crankcheck-grade.1 -P ManPage.cmake
# NAME is the page's first line (the command's purpose), SYNOPSIS its usage line, DESCRIPTION the whole help as
# preformatted text. The program is run without a shell.
cmake_minimum_required(VERSION 3.25)
foreach(v CRANKCHECK VERSION OUT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "ManPage.cmake: -D${v}=... is required")
  endif()
endforeach()
separate_arguments(words UNIX_COMMAND "${COMMAND}")
execute_process(COMMAND ${CRANKCHECK} ${words} --help RESULT_VARIABLE rc OUTPUT_VARIABLE help ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "ManPage.cmake: crankcheck ${COMMAND} --help failed (${rc}): ${err}")
endif()
string(REPLACE ";" " " title "${words}")
set(page_name "crankcheck")
if(title)
  string(REPLACE " " "-" dashed "${title}")
  set(page_name "crankcheck-${dashed}")
endif()
string(TOUPPER "${page_name}" upper)
# roff: a backslash is written \e; a line that starts with . or ' is protected by \&.
string(REPLACE "\\" "\\e" body "${help}")
string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" body "${body}")
string(REGEX MATCH "Usage: [^\n]*" usage "${help}")
string(REPLACE "Usage: " "" usage "${usage}")
# The purpose: the help's first paragraph (its wrapped lines before "Usage:"), as one line.
string(FIND "${help}" "\nUsage: " at)
string(SUBSTRING "${help}" 0 ${at} purpose)
string(REPLACE "\n" " " purpose "${purpose}")
string(REPLACE "\\" "\\e" purpose "${purpose}")
string(REPLACE "\\" "\\e" usage "${usage}")
string(REPLACE "-" "\\-" name_line "${page_name}")
file(WRITE ${OUT} ".TH ${upper} 1 \"\" \"crankcheck ${VERSION}\" \"crankcheck\"\n"
                  ".SH NAME\n${name_line} \\- ${purpose}\n"
                  ".SH SYNOPSIS\n.nf\n${usage}\n.fi\n"
                  ".SH DESCRIPTION\n.nf\n${body}.fi\n"
                  ".SH SEE ALSO\ncrankcheck(1); the documentation in share/crankcheck/docs of the install.\n")
