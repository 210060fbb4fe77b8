# The unit tests, folder by folder as the sources (included from tests/CMakeLists.txt).

# core
cocopp_unit_test(core/protocol SOURCES test_frame.cpp test_messages.cpp test_transport.cpp
                 LIBS cocopp_protocol)
cocopp_unit_test(core/case SOURCES test_settings.cpp test_registry.cpp test_path_problem.cpp
                 LIBS cocopp_core)
cocopp_unit_test(core/data
                 SOURCES test_interface.cpp test_restart_file.cpp test_calculix_interface_file.cpp
                 LIBS cocopp_core)

# mappers
cocopp_unit_test(mappers/interpolators
                 SOURCES test_interpolators.cpp test_interpolator_checks.cpp test_overlap.cpp
                 LIBS cocopp_mappers)
cocopp_unit_test(mappers/transformers SOURCES test_transformers.cpp LIBS cocopp_mappers)
cocopp_unit_test(mappers SOURCES test_mapper.cpp LIBS cocopp_mappers)

# solvers (the solver side: what runs in a solver process)
cocopp_unit_test(solvers/sdk SOURCES test_solver_sdk.cpp LIBS cocopp_sdk)
cocopp_unit_test(solvers/tube
  SOURCES test_banded_solver.cpp test_tube_input.cpp test_tube_flow.cpp test_tube_structure.cpp
          test_tube_ringmodel.cpp test_tube_wave_speed.cpp test_tube_restart.cpp
  LIBS cocopp_tube_models)
# The example input files are read from the source tree (also without ctest's environment).
target_compile_definitions(${COCOPP_LAST_TEST} PRIVATE
  COCOPP_TUBE_EXAMPLES_DIR="${PROJECT_SOURCE_DIR}/examples/tube")
# Runs the executables, so building it builds them.
cocopp_unit_test(solvers/tube SUFFIX executables SOURCES test_tube_executables.cpp
  DEPENDS cocopp-tube-flow cocopp-tube-structure cocopp-tube-ringmodel)
target_compile_definitions(${COCOPP_LAST_TEST} PRIVATE
  COCOPP_TUBE_EXAMPLES_DIR="${PROJECT_SOURCE_DIR}/examples/tube"
  COCOPP_TUBE_FLOW_EXECUTABLE="$<TARGET_FILE:cocopp-tube-flow>"
  COCOPP_TUBE_STRUCTURE_EXECUTABLE="$<TARGET_FILE:cocopp-tube-structure>"
  COCOPP_TUBE_RINGMODEL_EXECUTABLE="$<TARGET_FILE:cocopp-tube-ringmodel>")
# ccx's SOLVER=SUITESPARSE at its interface (scripts/calculix/06-suitesparse-solver.patch),
# linked with ccx's objects as cocopp-ccx is.
if(COCOPP_HAVE_COUPLED_CCX)
  cocopp_unit_test(solvers/calculix SOURCES test_ccx_suitesparse.cpp
                   LIBS cocopp_ccx_objects Eigen3::Eigen LABELS ccx)
endif()

# solver wrappers (the coupler side)
cocopp_unit_test(solver_wrappers/process
                 SOURCES test_child_process.cpp test_process_solver_wrapper.cpp
                 LIBS cocopp_solver_wrappers DEPENDS cocopp-test-solver)
cocopp_unit_test(solver_wrappers/mapped SOURCES test_mapped_solver_wrapper.cpp test_exact_round_trip.cpp
                 LIBS cocopp_solver_wrappers)
cocopp_unit_test(solver_wrappers/group SOURCES test_group_solver_wrapper.cpp
                 LIBS cocopp_solver_wrappers)
# The OpenFOAM wrapper's coupler side (dictionary reading, case checks): no OpenFOAM needed.
cocopp_unit_test(solver_wrappers/openfoam SOURCES test_openfoam_case.cpp
                 LIBS cocopp_solver_wrappers)
# The CalculiX wrapper: deck reading and loads without ccx; the ccx runs where ccx is
# (COCOPP_HAVE_CALCULIX, found once in solvers/calculix).
cocopp_unit_test(solver_wrappers/calculix SOURCES test_calculix_deck.cpp test_displacement_drive_faces.cpp
                 test_displacement_drive_compliance.cpp test_reynolds_film.cpp
                 test_probed_film.cpp
                 test_interface_loads_totals.cpp
                 LIBS cocopp_solver_wrappers)
if(COCOPP_HAVE_CALCULIX)
  cocopp_unit_test(solver_wrappers/calculix SUFFIX ccx
                   SOURCES test_calculix_ccx.cpp test_calculix_state_reset.cpp
                           test_calculix_displacement_drive.cpp
                   LIBS cocopp_solver_wrappers LABELS ccx)
  if(COCOPP_HAVE_PATCHED_CCX)  # the restart of plastic models needs the patched ccx
    target_compile_definitions(${COCOPP_LAST_TEST} PRIVATE COCOPP_HAVE_PATCHED_CCX=1
                               COCOPP_PATCHED_CCX="${COCOPP_CALCULIX_DIR}/bin/ccx")
  endif()
  if(COCOPP_HAVE_COUPLED_CCX)  # mode: persistent (cocopp-ccx, found next to the tests' cocopp)
    target_compile_definitions(${COCOPP_LAST_TEST} PRIVATE COCOPP_HAVE_COUPLED_CCX=1)
    add_dependencies(${COCOPP_LAST_TEST} cocopp-ccx)
  endif()
endif()

# coupler
cocopp_unit_test(coupler/coupled_solvers
  SOURCES test_coupled_solvers.cpp test_ibqn.cpp test_iqnism.cpp test_scaling.cpp
          test_coupled_solver_state.cpp
  LIBS cocopp_coupling)
cocopp_unit_test(coupler/coupled_solvers/models
  SOURCES test_cross_projection.cpp test_ls.cpp test_multi_vector.cpp test_qr_factorization.cpp
  LIBS cocopp_coupling)
cocopp_unit_test(coupler/schemes SOURCES test_waveform.cpp LIBS cocopp_coupling)
cocopp_unit_test(coupler/convergence SOURCES test_convergence.cpp LIBS cocopp_coupling)
cocopp_unit_test(coupler/predictors SOURCES test_predictors.cpp LIBS cocopp_coupling)
# The HDF5 results file (read back with the C API and with h5py), the JSON run summary and the
# watchpoints.
cocopp_unit_test(coupler/results
  SOURCES test_results_writer.cpp test_results_reader.cpp test_run_summary.cpp
          test_results_python.cpp test_watchpoints.cpp test_state_file.cpp
  LIBS cocopp_coupling)
cocopp_unit_test(coupler/app SOURCES test_components.cpp test_case_lock.cpp LIBS cocopp_app)
