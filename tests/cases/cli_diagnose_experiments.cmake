# demfit diagnose on a study with several experiments: two analytic experiments
# sharing the variables, both matched to the same data with a hidden stiffening. The diagnosis must
# run through the experiments (curves "<experiment>/response") and name the hidden effect, as it
# does for the single-model study of tests/diagnose/cli_diagnose.cmake.
# Inputs: DEMFIT (executable), STUDY (study file), OUT (scratch).
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${DEMFIT} diagnose ${STUDY} --out ${OUT} --no-plots --jobs 2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "diagnose of an experiments study failed (${rc}): ${out} ${err}")
endif()
if(NOT out MATCHES "verdict: missing effect identified" OR NOT out MATCHES "stiffening")
  message(FATAL_ERROR "expected the hidden effect 'stiffening' to be named, got: ${out}")
endif()
if(NOT out MATCHES "first.response" AND NOT out MATCHES "second.response")
  message(FATAL_ERROR "expected the misfit located in an experiment's target, got: ${out}")
endif()
foreach(f report.md diagnosis.json)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "missing output ${OUT}/${f}")
  endif()
endforeach()
