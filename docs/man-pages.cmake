# Writes a man page per program and per subcommand from their own --help, through help2man.
# cmake -DHELP2MAN=... -DOUTPUT_DIR=... -DVERSION=... -DPROGRAMS="path1;path2;..." -P man-pages.cmake
# The subcommands are those the program's --help lists under "Subcommands:", so a new one gets its
# page without a change here. A page is named after what the user types: swath-plan.1 for
# `swath plan` (help2man names a page after the program it runs: a small script of that name runs
# the subcommand).
foreach(var HELP2MAN OUTPUT_DIR VERSION PROGRAMS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "man-pages.cmake: ${var} not given")
  endif()
endforeach()

file(MAKE_DIRECTORY "${OUTPUT_DIR}")
file(GLOB stale "${OUTPUT_DIR}/*.1")
if(stale)
  file(REMOVE ${stale})
endif()
set(wrappers "${OUTPUT_DIR}/.wrappers")
file(REMOVE_RECURSE "${wrappers}")
file(MAKE_DIRECTORY "${wrappers}")

function(swath_man_page command page description)
  execute_process(
    COMMAND "${HELP2MAN}" --no-info --no-discard-stderr "--version-string=${VERSION}"
            "--name=${description}" "--output=${OUTPUT_DIR}/${page}.1" "${command}"
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "help2man failed for ${command}: ${err}")
  endif()
endfunction()

foreach(program IN LISTS PROGRAMS)
  get_filename_component(name "${program}" NAME)
  execute_process(COMMAND "${program}" --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${program} --help exited ${rc}")
  endif()
  string(REGEX MATCH "^[^\n]*" first_line "${help}")
  string(REGEX REPLACE "^${name}: " "" description "${first_line}")
  swath_man_page("${program}" "${name}" "${description}")

  # The subcommands: the lines "  NAME   DESCRIPTION" after "Subcommands:" up to a blank line.
  # (a description's own semicolons would split CMake's list: held as a placeholder meanwhile)
  string(REPLACE ";" "@SEMICOLON@" help_text "${help}")
  string(REPLACE "\n" ";" lines "${help_text}")
  set(in_list FALSE)
  foreach(line IN LISTS lines)
    if(line MATCHES "^[Ss][Uu][Bb][Cc][Oo][Mm][Mm][Aa][Nn][Dd][Ss]:")
      set(in_list TRUE)
    elseif(in_list AND line MATCHES "^  ([a-z][a-z0-9-]*)[ \t]+(.*)$")
      set(sub "${CMAKE_MATCH_1}")
      string(REPLACE "@SEMICOLON@" ";" sub_description "${CMAKE_MATCH_2}")
      set(wrapper "${wrappers}/${name}-${sub}")
      file(WRITE "${wrapper}" "#!/bin/sh\nexec '${program}' ${sub} \"$@\"\n")
      file(CHMOD "${wrapper}" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
           GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
      swath_man_page("${wrapper}" "${name}-${sub}" "${sub_description}")
    elseif(in_list AND NOT line MATCHES "^  ")
      set(in_list FALSE)
    endif()
  endforeach()
endforeach()
file(REMOVE_RECURSE "${wrappers}")
