# vd: the two commands of the README are `make demo` and `make test`.
# Both set the workspace up first (idempotent: a second run installs nothing).
SHELL := /bin/bash
ENV := tools/env.sh

.PHONY: setup demo test fuzz bench clean

setup:
	@bash tools/setup.sh

demo: setup
	@$(ENV) python -m vd_events.cli.demo

test: setup
	@$(ENV) python -m pytest -q

# the fuzz suite with many more examples (tests/fuzz; `make test` runs it briefly) and
# the fault tests with SIGTERM and random signal times
fuzz: setup
	@HYPOTHESIS_PROFILE=fuzz $(ENV) python -m pytest -q tests/fuzz tests/integration/test_faults.py

bench: setup
	@$(ENV) python -m vd_events.cli.main bench

clean:
	rm -rf build install log out
