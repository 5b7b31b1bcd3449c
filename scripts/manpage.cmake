# Writes the man page viscolube.1 from the program's --help texts.
#   cmake -DCLI=path/to/viscolube -DOUT=viscolube.1 -DVERSION=x.y.z -DDB=scratch.db
#         -P scripts/manpage.cmake
# Each text goes in verbatim (.nf), under a heading per command, so that the
# page says exactly what --help says.
foreach(v CLI OUT VERSION DB)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "manpage.cmake: -D${v}=... is required")
  endif()
endforeach()

# roff: a backslash is \e; a line starting with . or ' would be a request
function(vl_roff text out)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

function(vl_help out)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env VISCOLUBE_DB=${DB} ${CLI} ${ARGN}
                  OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "manpage.cmake: `viscolube ${ARGN}` exited ${rc}")
  endif()
  vl_roff("${text}" text)
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

string(TIMESTAMP today "%Y-%m-%d" UTC)
vl_help(main --help)
set(page ".TH VISCOLUBE 1 \"${today}\" \"viscolube ${VERSION}\" \"User Commands\"
.SH NAME
viscolube \\- friction of wet rubber contacts from a material database
.SH SYNOPSIS
.B viscolube
[\\fB\\-\\-db\\fR \\fIPATH\\fR] [\\fB\\-\\-quiet\\fR] \\fINOUN\\fR \\fIVERB\\fR ...
.br
.B viscolube
\\fB\\-\\-version\\fR | \\fB\\-\\-help\\fR
.SH DESCRIPTION
The text of \\fBviscolube \\-\\-help\\fR:
.PP
.nf
${main}.fi
.SH COMMANDS
Each section is the text of \\fBviscolube\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR.
")
foreach(cmd "compound" "compound add" "surface" "surface add" "fluid" "fluid add" "run" "study"
        "friction" "compare" "flattening")
  separate_arguments(args UNIX_COMMAND "${cmd}")
  vl_help(text ${args} --help)
  string(APPEND page ".SS ${cmd}\n.nf\n${text}.fi\n")
endforeach()
string(APPEND page ".SH FILES
.TP
.I $VISCOLUBE_DB, $XDG_DATA_HOME/viscolube/materials.db, ~/.local/share/viscolube/materials.db
the material database (SQLite), the first that applies; created on first use
.SH SEE ALSO
README.md and docs/ of the source tree: docs/CLI.md (the command line in full),
docs/MODEL.md (the model), docs/FORMATS.md (every file read or written),
docs/NUMERICS.md.
")
file(WRITE ${OUT} "${page}")
