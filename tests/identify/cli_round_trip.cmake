# End-to-end check of `demfit identify`, `report` and `export` on the analytic model:
#   cmake -DDEMFIT=<exe> -DDATA=<tests/identify/data> -DOUT=<folder> -P cli_round_trip.cmake
# The numbers are checked by the library tests; this checks the plumbing and the messages.
file(REMOVE_RECURSE ${OUT})
function(run expect_code)
  execute_process(COMMAND ${DEMFIT} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expect_code)
    message(FATAL_ERROR "demfit ${ARGN}: exit ${code}, expected ${expect_code}\n${out}\n${err}")
  endif()
  set(last_out "${out}" PARENT_SCOPE)
  set(last_err "${err}" PARENT_SCOPE)
endfunction()

run(0 identify ${DATA}/analytic_study.json --out ${OUT}/study --jobs 2)
foreach(f study.db best_parameters.json evaluations.csv iterations.csv report.md study_resolved.json
          target_response.csv best_response.csv)
  if(NOT EXISTS ${OUT}/study/${f})
    message(FATAL_ERROR "identify did not write ${f}")
  endif()
endforeach()
file(READ ${OUT}/study/best_parameters.json best)
string(JSON amplitude GET "${best}" variables amplitude value)
if(NOT amplitude MATCHES "^1\\.(2999|300)")
  message(FATAL_ERROR "identified amplitude ${amplitude}, expected 1.3 to 1e-3")
endif()

# An existing store is refused without --resume; with --resume a finished study reruns nothing.
run(1 identify ${DATA}/analytic_study.json --out ${OUT}/study)
if(NOT last_err MATCHES "demfit: error: study store .* already exists; pass --resume")
  message(FATAL_ERROR "unexpected message: ${last_err}")
endif()
run(0 identify ${DATA}/analytic_study.json --out ${OUT}/study --resume --no-plots)
if(last_err MATCHES "run [0-9]+/[0-9]+ ")
  message(FATAL_ERROR "--resume of a finished study repeated runs:\n${last_err}")
endif()

# Malformed study: one line naming the field.
run(1 identify ${DATA}/malformed_study.json --out ${OUT}/bad)
if(NOT last_err MATCHES "^demfit: error: study: variables\\[0\\]\\.lowr: unknown key; did you mean \"lower\"\\?[^\n]*\n$")
  message(FATAL_ERROR "unexpected message: ${last_err}")
endif()

run(0 report ${OUT}/study/study.db --out ${OUT}/rebuilt --no-plots)
if(NOT EXISTS ${OUT}/rebuilt/report.md)
  message(FATAL_ERROR "report did not rebuild report.md")
endif()
# export refuses a study whose model is not a DEM case: the analytic model has no
# LS-DYNA meaning. The card layout itself is checked by test_lsdyna_export.
run(1 export ${OUT}/study/study.db --lsdyna ${OUT}/out.k)
if(NOT last_err MATCHES "^demfit: error: export: .*analytic.* not a DEM case[^\n]*\n$" OR EXISTS ${OUT}/out.k)
  message(FATAL_ERROR "export of an analytic study was not refused cleanly: ${last_err}")
endif()

# A study with two experiments: both experiments' targets and curves, the resolved study in the
# experiments form, and export refused (no single full parameter set).
run(0 identify ${DATA}/two_experiment_study.json --out ${OUT}/experiments --jobs 2 --no-plots)
foreach(f target_coarse.response.csv best_coarse.response.csv target_fine.response.csv best_fine.response.csv)
  if(NOT EXISTS ${OUT}/experiments/${f})
    message(FATAL_ERROR "identify of an experiments study did not write ${f}")
  endif()
endforeach()
file(READ ${OUT}/experiments/study_resolved.json resolved)
string(JSON second GET "${resolved}" experiments 1 name)
if(NOT second STREQUAL "fine")
  message(FATAL_ERROR "study_resolved.json lacks the experiments: ${resolved}")
endif()
run(1 export ${OUT}/experiments/study.db --lsdyna ${OUT}/experiments.k)
if(NOT last_err MATCHES "several experiments; export needs a single-model study" OR EXISTS ${OUT}/experiments.k)
  message(FATAL_ERROR "export of an experiments study: ${last_err}")
endif()

# A study with a cheap level: its runs first (the cheap model is the analytic curve at 9 points),
# named in the report; a resume repeats none of them.
run(0 identify ${DATA}/cheap_level_study.json --out ${OUT}/cheap --jobs 2 --no-plots)
if(NOT last_err MATCHES "cheap level run 12/12")
  message(FATAL_ERROR "identify with a cheap level did not run it:\n${last_err}")
endif()
file(READ ${OUT}/cheap/report.md report)
if(NOT report MATCHES "cheap level [^\n]*12 runs \\(0 failed\\)")
  message(FATAL_ERROR "report.md does not name the cheap level:\n${report}")
endif()
run(0 identify ${DATA}/cheap_level_study.json --out ${OUT}/cheap --resume --no-plots)
if(last_err MATCHES "cheap level run|run [0-9]+/[0-9]+ ")
  message(FATAL_ERROR "--resume of a study with a cheap level repeated runs:\n${last_err}")
endif()
