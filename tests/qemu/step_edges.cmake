# Step/dir output of the STM32F4 firmware in QEMU (included by tests/qemu/CMakeLists.txt): the
# App<Board> firmware runs a job streamed by `curvestep stream`, its TIM2 interrupt plays the edges
# through GPIOA BSRR, and step_edges_test.py checks the BSRR writes in QEMU's -d unimp log: net
# steps per axis against the job file, the whole step walk against the captured setpoints, DIR
# only while STEP is low, STEP alternating. Order and counts only: QEMU 7.2's TIM2 has no compare
# interrupt and a wrong update period, so it plays the edges late (65.5 ms of schedule per update
# interrupt) and the board, seeing an emulator, plays the oldest edge when its ring is full. The
# helix is made coarser (--steps-per-mm) and faster (--feed) to keep its run short.
# docs/boards.md, "Step edges in QEMU".
# Skipped (77) while curvestep has no `stream`.
if(TARGET curvestep)
  set(machine ${qemu_dir}/wire_exact_machine.json)
  foreach(case
          "seed_cubic|X, Y"
          "helix|--steps-per-mm;0.5,0.5,4;--feed;200|X, Y, Z")
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 job)
    list(GET parts -1 what)
    set(options ${parts})
    list(REMOVE_AT options 0 -1)
    set(name "qemu: stm32f4 firmware steps ${job} through TIM2 and GPIOA BSRR, counts and order (${what})")
    add_test(NAME "${name}"
             COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/step_edges_test.py stm32f4
                     ${PROJECT_BINARY_DIR}/qemu-stm32f4/bin/curvestep_stm32f4_firmware.elf $<TARGET_FILE:curvestep>
                     ${PROJECT_SOURCE_DIR}/examples/jobs/${job}.json ${machine} ${options})
    set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                         FIXTURES_REQUIRED qemu_stm32f4_images)
  endforeach()
endif()
