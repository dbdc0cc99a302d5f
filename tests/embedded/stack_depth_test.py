#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""boards/stm32_common/stack_depth.py on hand-written call graphs (the VCG that GCC's
-fcallgraph-info=su writes): the deepest chain's frames are added, interrupt handlers and their
exception frames are added on top, calls across files resolve by symbol (complete-object
constructors C1 to their base-object C2 definition), unknown callees and indirect calls count 64
bytes, recursion and dynamic frames fail. Expected values are sums worked out by hand."""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "boards", "stm32_common", "stack_depth.py")


def node(title, name, frame, kind="static"):
    return 'node: { title: "%s" label: "%s\\nfile.cpp:1:1\\n%d bytes (%s)" }\n' % (title, name, frame, kind)


def external(title):
    return 'node: { title: "%s" label: "%s\\n<built-in>" shape : ellipse }\n' % (title, title)


def edge(a, b):
    return 'edge: { sourcename: "%s" targetname: "%s" label: "file.cpp:2:2" }\n' % (a, b)


def run(files, *args):
    with tempfile.TemporaryDirectory() as d:
        paths = []
        for i, text in enumerate(files):
            p = os.path.join(d, "f%d.ci" % i)
            with open(p, "w", encoding="utf-8") as f:
                f.write('graph: { title: "f%d.cpp"\n' % i + text + "}\n")
            paths.append(p)
        out = os.path.join(d, "out.json")
        r = subprocess.run([sys.executable, TOOL, "--json", out, *args, *paths], capture_output=True, text=True)
        result = json.load(open(out, encoding="utf-8")) if os.path.exists(out) else None
        return r.returncode, r.stdout, result


failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED:", what)


# Main file: Reset_Handler (8) -> curvestep_main (32) -> {big (400) -> leaf (16), small (40) -> __aeabi_dadd}
# Deepest: 8 + 32 + 400 + 16 = 456 (the other branch: 8 + 32 + 40 + 64 = 144).
# Second file: SysTick_Handler (16) -> _ZN1XC1Ev (the C1 constructor, defined as _ZN1XC2Ev: 24) and an
# indirect call (64): 16 + 64 = 80, + 32 exception frame = 112. USART1_IRQHandler (8) alone: 8 + 32 = 40.
main = (node("f0.cpp:Reset_Handler", "Reset_Handler", 8) + node("curvestep_main", "curvestep_main", 32) +
        node("f0.cpp:_Z3bigv", "big()", 400) + node("f0.cpp:_Z4leafv", "leaf()", 16) +
        node("f0.cpp:_Z5smallv", "small()", 40) + external("__aeabi_dadd") +
        edge("f0.cpp:Reset_Handler", "curvestep_main") + edge("curvestep_main", "f0.cpp:_Z3bigv") +
        edge("f0.cpp:_Z3bigv", "f0.cpp:_Z4leafv") + edge("curvestep_main", "f0.cpp:_Z5smallv") +
        edge("f0.cpp:_Z5smallv", "__aeabi_dadd"))
handlers = (node("SysTick_Handler", "SysTick_Handler", 16) + node("f1.cpp:_ZN1XC2Ev", "X::X()", 24) +
            'node: { title: "__indirect_call" label: "Indirect Call Placeholder" shape : ellipse }\n' +
            edge("SysTick_Handler", "_ZN1XC1Ev") + edge("SysTick_Handler", "__indirect_call") +
            node("USART1_IRQHandler", "USART1_IRQHandler", 8))

code, out, result = run([main, handlers])
check(code == 0, "a clean graph passes (%s)" % out)
check(result["main_bytes"] == 456, "main depth 456, got %s" % result["main_bytes"])
check(result["interrupt_bytes"] == {"SysTick_Handler": 112, "USART1_IRQHandler": 40},
      "interrupt depths 112 and 40, got %s" % result["interrupt_bytes"])
check(result["worst_case_bytes"] == 456 + 112 + 40, "worst case 608, got %s" % result["worst_case_bytes"])
check([c.split(" (")[0] for c in result["deepest_chain"]] == ["Reset_Handler", "curvestep_main", "big()", "leaf()"],
      "deepest chain Reset_Handler -> curvestep_main -> big -> leaf, got %s" % result["deepest_chain"])
check("__aeabi_dadd" in result["unknown_callees"], "libgcc callee listed as unknown")

code, out, result = run([main, handlers], "--fpu")
check(result["worst_case_bytes"] == 456 + (16 + 64 + 104) + (8 + 104), "FPU frames: 104 bytes per handler")

code, out, result = run([main, handlers], "--limit", "600")
check(code == 1 and "exceeds the reserved 600" in out, "over the limit fails")
code, out, result = run([main, handlers], "--limit", "608")
check(code == 0, "at the limit passes")

recursive = main + edge("f0.cpp:_Z4leafv", "f0.cpp:_Z3bigv")
code, out, result = run([recursive, handlers])
check(code == 1 and "recursion" in out, "recursion fails")

dynamic = main.replace("16 bytes (static)", "16 bytes (dynamic)")
code, out, result = run([dynamic, handlers])
check(code == 1 and "dynamic" in out, "a dynamic frame fails")

print("PASS" if not failures else "FAIL: %d check(s)" % len(failures))
sys.exit(1 if failures else 0)
