# Surface meshes through the command line: the ONERA M6 case, a station-defined wing
# and imported Plot3D blocks, checked by an independent VTK reader; and each kind of
# bad input rejected with one line naming file:line.
set(surface_cases ${CMAKE_CURRENT_LIST_DIR}/surface)
set(surface_check ${CMAKE_CURRENT_LIST_DIR}/surface_check.py)
set(surface_output ${CMAKE_CURRENT_BINARY_DIR}/surface_regression)
file(MAKE_DIRECTORY ${surface_output})

add_test(NAME surface_onera_m6_generate
         COMMAND $<TARGET_FILE:mixmesh-cli> surface ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml
                 -o ${surface_output}/onera_m6_surface.vtu)
add_test(NAME surface_onera_m6_check
         COMMAND ${MIXMESH_PYTHON} ${surface_check} mesh ${surface_output}/onera_m6_surface.vtu --wing-faces 8000)
set_property(TEST surface_onera_m6_generate APPEND PROPERTY FIXTURES_SETUP surface_onera_m6_generate)
set_tests_properties(surface_onera_m6_check PROPERTIES FIXTURES_REQUIRED surface_onera_m6_generate)

add_test(NAME surface_stations_generate
         COMMAND $<TARGET_FILE:mixmesh-cli> surface ${surface_cases}/naca_stations.toml
                 -o ${surface_output}/stations_surface.vtu)
add_test(NAME surface_stations_check
         COMMAND ${MIXMESH_PYTHON} ${surface_check} mesh ${surface_output}/stations_surface.vtu --wing-faces 2520)
set_property(TEST surface_stations_generate APPEND PROPERTY FIXTURES_SETUP surface_stations_generate)
set_tests_properties(surface_stations_check PROPERTIES FIXTURES_REQUIRED surface_stations_generate)

add_test(NAME surface_import_generate
         COMMAND $<TARGET_FILE:mixmesh-cli> surface ${surface_cases}/import_box.toml
                 -o ${surface_output}/import_box_surface.vtu)
add_test(NAME surface_import_check
         COMMAND ${MIXMESH_PYTHON} ${surface_check} mesh ${surface_output}/import_box_surface.vtu --wing-faces 45)
set_property(TEST surface_import_generate APPEND PROPERTY FIXTURES_SETUP surface_import_generate)
set_tests_properties(surface_import_check PROPERTIES FIXTURES_REQUIRED surface_import_generate)

# name, config, expected error (regular expression on the one stderr line)
set(surface_bad_inputs
    "negative_chord|negative_chord.toml|negative_chord\\.toml:3:[0-9]+: .*root_chord"
    "unknown_key|unknown_key.toml|unknown_key\\.toml:9:[0-9]+: unknown key 'surface\\.spanwise_cell'"
    "missing_airfoil|missing_airfoil.toml|missing_airfoil\\.toml:2:[0-9]+: .*no_such_airfoil\\.dat"
    "unreadable_airfoil|unreadable_airfoil.toml|unreadable\\.dat:3: expected two numbers"
    "crossing_surfaces|crossing.toml|crossing\\.dat:[0-9]+: the upper and lower surfaces cross"
    "too_few_points|few_points.toml|few_points\\.dat.*too few points")
foreach(entry IN LISTS surface_bad_inputs)
  string(REPLACE "|" ";" fields "${entry}")
  list(GET fields 0 name)
  list(GET fields 1 config)
  list(GET fields 2 pattern)
  add_test(NAME surface_rejects_${name}
           COMMAND ${MIXMESH_PYTHON} ${surface_check} fails "${pattern}" --
                   $<TARGET_FILE:mixmesh-cli> surface ${surface_cases}/${config} -o ${surface_output}/${name}.vtu)
endforeach()

set_tests_properties(surface_onera_m6_generate surface_onera_m6_check surface_stations_generate
                     surface_stations_check surface_import_generate surface_import_check
                     PROPERTIES LABELS regression)
foreach(entry IN LISTS surface_bad_inputs)
  string(REPLACE "|" ";" fields "${entry}")
  list(GET fields 0 name)
  set_tests_properties(surface_rejects_${name} PROPERTIES LABELS regression)
endforeach()
