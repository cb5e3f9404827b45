# demfit diagnose end to end. Inputs: DEMFIT (executable), DATA (tests/diagnose/data), OUT (scratch).
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT} --no-plots --jobs 2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "diagnose failed (${rc}): ${out} ${err}")
endif()
if(NOT out MATCHES "verdict: missing effect identified")
  message(FATAL_ERROR "expected an identified effect, got: ${out}")
endif()
if(NOT out MATCHES "stiffening")
  message(FATAL_ERROR "expected the hidden effect 'stiffening' to be named, got: ${out}")
endif()
foreach(f report.md report.html diagnosis.json)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "missing output ${OUT}/${f}")
  endif()
endforeach()
file(READ ${OUT}/diagnosis.json json)
string(JSON effect GET "${json}" effect)
if(NOT effect STREQUAL "stiffening")
  message(FATAL_ERROR "diagnosis.json names '${effect}', expected 'stiffening'")
endif()
# Without the right candidate: no wrong name.
execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT}/without --no-plots
                        --effects toe_shift,yield_drop
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "verdict: unexplained structural residual")
  message(FATAL_ERROR "expected an unexplained structural residual (${rc}): ${out} ${err}")
endif()
execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT}/bad --effects cohesion
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "demfit: error: --effects: unknown effect 'cohesion'")
  message(FATAL_ERROR "an unknown effect must be refused with a one-line error (${rc}): ${err}")
endif()
# --scatter-replicas: refused when negative; on the smooth analytic model the measured scatter is
# below the threshold, so the noise model stays white and the same effect is named.
execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT}/bad_replicas
                        --scatter-replicas -2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "demfit: error: --scatter-replicas: must be >= 0" OR EXISTS ${OUT}/bad_replicas)
  message(FATAL_ERROR "a negative --scatter-replicas must be refused with a one-line error, nothing written (${rc}): ${err}")
endif()
# Each option value below is refused with a one-line error naming the option, nothing written.
foreach(refused "--data-scatter;-0.5" "--data-scatter;nan" "--data-scatter;17" "--refit-search;-1"
                "--refit-search;401")
  list(GET refused 0 option)
  execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT}/refused ${refused}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "demfit: error: ${option}: " OR EXISTS ${OUT}/refused)
    message(FATAL_ERROR "${refused} must be refused with a one-line error, nothing written (${rc}): ${err}")
  endif()
endforeach()
execute_process(COMMAND ${DEMFIT} diagnose ${DATA}/hidden_stiffening_study.json --out ${OUT}/replicas --no-plots
                        --jobs 2 --scatter-replicas 3
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "stiffening")
  message(FATAL_ERROR "with --scatter-replicas 3 the hidden stiffening must still be named (${rc}): ${out} ${err}")
endif()
file(READ ${OUT}/replicas/diagnosis.json json)
string(JSON runs GET "${json}" targets 0 model_scatter runs)
string(JSON whitened GET "${json}" targets 0 whitened)
string(JSON data_scatter GET "${json}" data_scatter_ratio)
string(JSON refit_search GET "${json}" refit_search_evaluations)
if(NOT refit_search EQUAL 0)
  message(FATAL_ERROR "diagnosis.json must record the surrogate search's runs per re-fit (0 by default), got ${refit_search}")
endif()
if(NOT data_scatter EQUAL 0)
  message(FATAL_ERROR "diagnosis.json must record the data scatter ratio used (0 by default), got ${data_scatter}")
endif()
if(NOT runs EQUAL 4 OR whitened)
  message(FATAL_ERROR "expected the scatter measured from 4 runs and left out of the noise model, got runs ${runs}, whitened ${whitened}")
endif()
