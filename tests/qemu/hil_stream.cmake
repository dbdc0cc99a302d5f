# HIL streams against the emulated STM32F4 (included by tests/qemu/CMakeLists.txt): the App<Board>
# firmware in QEMU receives a job from `curvestep stream` over -serial pty; its setpoint stream must
# match `curvestep sim` within 1 µm (float firmware). Skipped (77) while curvestep has no `stream`.
# The STM32F1 (Q16.16, bit-identical) variant cannot run: its firmware needs 18.5 KiB of SRAM with its
# worst-case stack, QEMU's STM32F100 has 8 KiB (docs/boards.md, "Footprint"). In its place the same Cortex-M3 + Q16.16 firmware runs on QEMU's
# netduino2 (STM32F205: Cortex-M3, F2/F4 peripheral map), with the F1 firmware's application
# (App<Board, Q16_16, 16, 8>: boards/stm32f4/CMakeLists.txt), and must match sim bit for bit.
# The Cortex-M3 image and its handshake need no host tool.
add_test(NAME "qemu: stm32f2-m3 images cross-build (Cortex-M3, Q16.16 firmware)"
         COMMAND ${qemu_dir}/build_image.sh stm32f2-m3 ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/qemu-stm32f2-m3
                 curvestep_stm32f4_firmware)
set_tests_properties("qemu: stm32f2-m3 images cross-build (Cortex-M3, Q16.16 firmware)" PROPERTIES
                     LABELS qemu TIMEOUT 900 FIXTURES_SETUP qemu_stm32f2-m3_images)
# It announces the F1's queue and look-ahead (16, 8), which the streams below replay.
set(name "qemu: Cortex-M3 Q16.16 firmware answers Hello with the F1 queue and look-ahead")
add_test(NAME "${name}"
         COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/firmware_test.py stm32f2-m3
                 ${PROJECT_BINARY_DIR}/qemu-stm32f2-m3/bin/curvestep_stm32f4_firmware.elf)
set_tests_properties("${name}" PROPERTIES LABELS qemu TIMEOUT 90 FIXTURES_REQUIRED qemu_stm32f2-m3_images)
if(TARGET curvestep)
  # wire_exact_machine.json: the example machine with no rapid field (the protocol has none: the
  # device runs rapids at v_max) and tolerance / junction deviation exact in Q16.16; with
  # --round-weights the job's weights are rounded to Q16.16 too. Then the job means the same to
  # sim and to the device, which is what bit-identity needs.
  set(machine ${qemu_dir}/wire_exact_machine.json)
  foreach(job seed_cubic inch_square every_type)
    set(name "qemu: stm32f4 firmware streams ${job} within 1 um of curvestep sim")
    add_test(NAME "${name}"
             COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/hil_stream_test.py stm32f4
                     ${PROJECT_BINARY_DIR}/qemu-stm32f4/bin/curvestep_stm32f4_firmware.elf $<TARGET_FILE:curvestep>
                     ${PROJECT_SOURCE_DIR}/examples/jobs/${job}.json ${machine} --round-weights --tolerance 0.001)
    set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                         FIXTURES_REQUIRED qemu_stm32f4_images)
    # The F1 executor on its own QEMU machine: the host plans (curvestep stream), the board replays.
    # wire_exact_machine_f1.json is the same machine with a tenth of the steps per mm: the F1 takes
    # 32 step edges a tick (StepRateTooHigh above), and steps do not enter the setpoints.
    set(name "qemu: stm32f1 executor streams ${job} bit-identical to curvestep sim")
    add_test(NAME "${name}"
             COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/hil_stream_test.py stm32f1
                     ${PROJECT_BINARY_DIR}/qemu-stm32f1/bin/curvestep_stm32f1_executor.elf $<TARGET_FILE:curvestep>
                     ${PROJECT_SOURCE_DIR}/examples/jobs/${job}.json ${qemu_dir}/wire_exact_machine_f1.json --round-weights --exact)
    set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                         FIXTURES_REQUIRED qemu_stm32f1_images)
    set(name "qemu: Cortex-M3 Q16.16 firmware streams ${job} bit-identical to curvestep sim")
    add_test(NAME "${name}"
             COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/hil_stream_test.py stm32f2-m3
                     ${PROJECT_BINARY_DIR}/qemu-stm32f2-m3/bin/curvestep_stm32f4_firmware.elf $<TARGET_FILE:curvestep>
                     ${PROJECT_SOURCE_DIR}/examples/jobs/${job}.json ${machine} --round-weights --exact)
    set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                         FIXTURES_REQUIRED qemu_stm32f2-m3_images)
  endforeach()
endif()
