#!/usr/bin/env python3
"""Prints the slowest tests of a cargo-nextest JUnit report (the `ci` profile writes
target/nextest/ci/junit.xml): `scripts/slowest-tests.py [REPORT] [N]`, N default 10."""

import sys
import xml.etree.ElementTree as ET

path = sys.argv[1] if len(sys.argv) > 1 else "target/nextest/ci/junit.xml"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 10
cases = [
    (float(c.get("time", "0")), f"{c.get('classname')} {c.get('name')}")
    for c in ET.parse(path).getroot().iter("testcase")
]
cases.sort(reverse=True)
print(f"the {min(n, len(cases))} slowest of {len(cases)} tests (seconds, debug):")
for seconds, name in cases[:n]:
    print(f"{seconds:8.2f}  {name}")
