# run(COMMAND...): runs a command in a -P script, stops the script with its
# output when it fails, prints its standard output and keeps it in
# `last_output`.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# skip_without_photos(SET_DIR): ends the calling script with SKIPPED (the
# test counts as skipped) when SET_DIR/images is missing.
macro(skip_without_photos set_dir)
  if(NOT EXISTS ${set_dir}/images)
    message(STATUS "SKIPPED: ${set_dir}/images not found (the real photo sets "
                   "live in ../shared/data beside the checkout)")
    return()
  endif()
endmacro()

# largest_model(EVAL_JSON PREFIX): reads a tmr_eval JSON report and sets, in
# the caller's scope, PREFIX_images (reference images), PREFIX_models,
# PREFIX_registered and PREFIX_rotation (median rotation error, degrees) of
# the largest model, PREFIX_total (images registered over all models),
# PREFIX_worst_rotation (the largest median rotation error of any model),
# PREFIX_reprojection (mean reprojection error of the largest model, px),
# PREFIX_wrong (number of models flagged as a wrong merge) and PREFIX_shared
# (images registered in more than one model).
function(largest_model eval_json prefix)
  file(READ ${eval_json} json)
  string(JSON reference GET "${json}" models 0 reference_images)
  string(JSON num_models LENGTH "${json}" models)
  set(registered 0)
  set(rotation 0)
  set(total 0)
  set(worst 0)
  set(wrong 0)
  math(EXPR last "${num_models} - 1")
  foreach(k RANGE ${last})
    string(JSON images GET "${json}" models ${k} registered_images)
    string(JSON flagged GET "${json}" models ${k} wrong_merge)
    string(JSON median GET "${json}" models ${k} rotation_error_deg median)
    math(EXPR total "${total} + ${images}")
    if(median GREATER worst)
      set(worst ${median})
    endif()
    if(flagged)
      math(EXPR wrong "${wrong} + 1")
    endif()
    if(images GREATER registered)
      set(registered ${images})
      set(rotation ${median})
      string(JSON reprojection GET "${json}" models ${k} mean_reprojection_error_px)
    endif()
  endforeach()
  set(${prefix}_images ${reference} PARENT_SCOPE)
  set(${prefix}_models ${num_models} PARENT_SCOPE)
  set(${prefix}_registered ${registered} PARENT_SCOPE)
  set(${prefix}_rotation ${rotation} PARENT_SCOPE)
  set(${prefix}_total ${total} PARENT_SCOPE)
  set(${prefix}_worst_rotation ${worst} PARENT_SCOPE)
  set(${prefix}_wrong ${wrong} PARENT_SCOPE)
  set(${prefix}_reprojection ${reprojection} PARENT_SCOPE)
  string(JSON shared GET "${json}" images_in_several_models)
  set(${prefix}_shared ${shared} PARENT_SCOPE)
  message(STATUS "${prefix}: ${num_models} models, largest ${registered} of "
                 "${reference} images, median rotation error ${rotation} deg, "
                 "${wrong} wrong merges")
endfunction()

# micro(OUT VALUE): OUT = VALUE x 10^6 as an integer (CMake has no floating
# point; compare decimals so).
macro(micro out value)
  if(NOT "${value}" MATCHES "^([0-9]+)(\\.([0-9]*))?$")
    message(FATAL_ERROR "not a plain decimal number: ${value}")
  endif()
  set(whole ${CMAKE_MATCH_1})
  string(SUBSTRING "${CMAKE_MATCH_3}000000" 0 6 fraction)
  math(EXPR ${out} "${whole}0 * 100000 + 1${fraction} - 1000000")
endmacro()

# expect_rotation_no_worse(TMR STOCK PERCENT SLACK LABEL): stops the script
# unless the median rotation error TMR is at most max(STOCK x PERCENT / 100,
# STOCK + SLACK) (degrees as decimals; SLACK in micro-degrees).
function(expect_rotation_no_worse tmr stock percent slack label)
  micro(stock_u ${stock})
  micro(tmr_u ${tmr})
  math(EXPR allowed "${stock_u} * ${percent} / 100")
  math(EXPR floor "${stock_u} + ${slack}")
  if(floor GREATER allowed)
    set(allowed ${floor})
  endif()
  if(tmr_u GREATER allowed)
    message(FATAL_ERROR "${label}: median rotation error ${tmr} deg, stock ${stock} deg")
  endif()
endfunction()

# score(PREFIX MODELS): scores the models in folder MODELS against the ground
# truth in ${WORK_DIR}/gt with tmr_eval (${WORK_DIR}/PREFIX.json) and sets
# the figures of largest_model(... PREFIX) in the caller's scope.
macro(score prefix models)
  run(${TMR_EVAL} --gt ${WORK_DIR}/gt --model ${models}
      --output_json ${WORK_DIR}/${prefix}.json)
  largest_model(${WORK_DIR}/${prefix}.json ${prefix})
endmacro()

# expect_fair_stock(PERCENT MAX_ROTATION): stops the script unless stock's
# largest model (stock_* from score(stock ...)) holds PERCENT% of the images
# with a median rotation error below MAX_ROTATION degrees: the scene is a
# fair test.
function(expect_fair_stock percent max_rotation)
  math(EXPR needed "(${stock_images} * ${percent} + 99) / 100")
  if(stock_registered LESS needed)
    message(FATAL_ERROR "stock: registered ${stock_registered} < ${percent}% of ${stock_images}")
  endif()
  if(stock_rotation GREATER_EQUAL ${max_rotation})
    message(FATAL_ERROR "stock: median rotation error ${stock_rotation} >= ${max_rotation} deg")
  endif()
endfunction()

# expect_as_good_as_stock(PREFIX LABEL): stops the script unless the largest
# model of PREFIX (score(PREFIX ...)) holds >= 98% of the images stock
# registers, with a median rotation error no worse than stock's up to
# bundle-adjustment noise (25% or 0.01 degrees, whichever is larger).
function(expect_as_good_as_stock prefix label)
  math(EXPR needed "(${stock_registered} * 98 + 99) / 100")
  if(${prefix}_registered LESS needed)
    message(FATAL_ERROR "${label}: registered ${${prefix}_registered} < 98% of stock's ${stock_registered}")
  endif()
  expect_rotation_no_worse(${${prefix}_rotation} ${stock_rotation} 125 10000 "${label}")
endfunction()

# differing_model_file(MODEL_A MODEL_B OUT): the first file of a COLMAP
# binary model (cameras, images, points3D, rigs, frames) that differs
# between the folders MODEL_A and MODEL_B, in OUT; empty when every one is
# byte-identical.
function(differing_model_file model_a model_b out)
  foreach(file cameras.bin images.bin points3D.bin rigs.bin frames.bin)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
                    ${model_a}/${file} ${model_b}/${file}
                    RESULT_VARIABLE differ)
    if(differ)
      set(${out} ${file} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()
