# expect_error.cmake — runs `${CDYN} ${ARGS}` and checks the bad-input contract
# (README.md, "Command line"; docs/outputs.md): exit status ${STATUS} (default 2) and
# exactly one line on stderr besides the run's warnings ("cdyn: warning: ..."),
# matching ${MATCH}.  With -DOUT=dir (a fresh directory the command was told to write
# to), also that the failed command left there no summary.json (a finished run) nor
# study.csv (a finished study): no output may look complete; and that the files of
# -DEXISTS (names under OUT: what a numerical failure keeps, e.g. history.csv) are there.
#   cmake -DCDYN=... -DARGS="a;b" -DMATCH=regex [-DSTATUS=2] [-DWORKDIR=dir] [-DOUT=dir] [-DEXISTS=f1;f2]
#         -P expect_error.cmake
if(NOT DEFINED STATUS)
  set(STATUS 2)
endif()
if(NOT DEFINED WORKDIR)
  set(WORKDIR ${CMAKE_CURRENT_BINARY_DIR})
endif()
if(DEFINED OUT)
  file(REMOVE_RECURSE ${OUT})
endif()
execute_process(COMMAND ${CDYN} ${ARGS} WORKING_DIRECTORY ${WORKDIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL STATUS)
  message(FATAL_ERROR "expected exit status ${STATUS}, got ${rc}\nstdout: ${out}\nstderr: ${err}")
endif()
string(REGEX REPLACE "cdyn: warning: [^\n]*\n" "" err "${err}")
string(REGEX MATCHALL "\n" newlines "${err}")
list(LENGTH newlines n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "expected one line on stderr, got ${n}:\n${err}")
endif()
if(NOT err MATCHES "${MATCH}")
  message(FATAL_ERROR "stderr does not match '${MATCH}':\n${err}")
endif()
foreach(marker summary.json study.csv)
  if(DEFINED OUT AND EXISTS ${OUT}/${marker})
    message(FATAL_ERROR "the failed command left ${OUT}/${marker}")
  endif()
endforeach()
foreach(f ${EXISTS})
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "the failed command did not keep ${OUT}/${f}")
  endif()
endforeach()
message(STATUS "ok: ${err}")
