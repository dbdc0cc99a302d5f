# The real-time benchmark (benchmarks/qemu/tick_budget.py; included by tests/qemu/CMakeLists.txt):
# a cheap run that checks only that its JSON is well formed and every figure is there, not the
# timings: the STM32F4 executor image built with CURVESTEP_TICK_PROFILE streams seed_cubic in QEMU
# (-icount). The full run (every image and job) is in docs/boards.md, "Real time".
add_test(NAME "qemu: stm32f4 tick-profile images cross-build (CURVESTEP_TICK_PROFILE)"
         COMMAND ${qemu_dir}/build_image.sh stm32f4 ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/qemu-profile-stm32f4
                 -DCURVESTEP_TICK_PROFILE=ON curvestep_stm32f4_executor)
set_tests_properties("qemu: stm32f4 tick-profile images cross-build (CURVESTEP_TICK_PROFILE)" PROPERTIES
                     LABELS qemu TIMEOUT 900 FIXTURES_SETUP qemu_stm32f4_profile_images)
if(TARGET curvestep)
  set(name "benchmark: stm32f4 executor instructions per tick and per piece in QEMU against the real-time budget (quick)")
  add_test(NAME "${name}"
           COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/benchmarks/qemu/tick_budget.py --quick
                   --curvestep $<TARGET_FILE:curvestep> --machine ${PROJECT_SOURCE_DIR}/examples/jobs/machine.json
                   --image stm32f4:executor:netduinoplus2:${PROJECT_BINARY_DIR}/qemu-profile-stm32f4/bin/curvestep_stm32f4_executor.elf
                   --job ${PROJECT_SOURCE_DIR}/examples/jobs/seed_cubic.json
                   --json ${PROJECT_BINARY_DIR}/qemu-profile-stm32f4/tick_budget_quick.json)
  set_tests_properties("${name}" PROPERTIES LABELS "benchmark;qemu" TIMEOUT 300
                       FIXTURES_REQUIRED qemu_stm32f4_profile_images)
endif()
