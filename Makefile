# LiftRemesh: every user-facing target first installs what is missing (scripts/install-deps.sh,
# a no-op costing a tenth of a second when everything is there).
#   make demo    remesh a FreeCAD-made bracket, print a quality summary
#   make test    build and run the C++ test suite and the FreeCAD tests
#   make test-freecad1  the same in a Debian 13 root (FreeCAD 1.0), cached in ~/.cache/liftremesh,
#                then the pip-installed module in FreeCAD (needs root)
#   make bench   time the CLI on ../shared/meshes, write docs/results.md, then make docs
#   make docs    write docs/cli.md and docs/report.md from the built CLI and module
#   make build   configure and build in build/ (Release)
#   make install link the FreeCAD add-on into FreeCAD's user Mod folder (after building)
#   make uninstall remove that link
#   make fuzz    libFuzzer targets under ASan and UBSan in build-fuzz/, FUZZ_SECONDS each (default 60)
#   make clean   remove build/, build-fuzz/ and out/

BUILD_DIR ?= build
OUT_DIR   ?= out
JOBS      ?= 2
# Debian's Python: it has numpy and finds FreeCAD (not the pyenv python3 first on PATH).
PYTHON    ?= /usr/bin/python3
CLI       := $(BUILD_DIR)/bin/liftremesh

.PHONY: all deps build test test-freecad1 demo bench docs fuzz install uninstall clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) --parallel $(JOBS)

test: deps build
	ctest --test-dir $(BUILD_DIR) --output-on-failure

test-freecad1:
	JOBS=$(JOBS) bash scripts/test-freecad1.sh

demo: deps build
	@mkdir -p $(OUT_DIR)
	$(PYTHON) scripts/make_demo_part.py $(OUT_DIR)/demo_part.stl
	$(CLI) $(OUT_DIR)/demo_part.stl $(OUT_DIR)/demo_remeshed.stl --report $(OUT_DIR)/demo_report.json
	@echo
	@$(PYTHON) scripts/report_summary.py $(OUT_DIR)/demo_report.json --check
	@echo "remeshed part: $(OUT_DIR)/demo_remeshed.stl (input $(OUT_DIR)/demo_part.stl)"

bench: deps build
	$(PYTHON) scripts/bench.py --cli $(CLI) --out $(OUT_DIR)/bench --results docs/results.md
	$(PYTHON) scripts/gen_docs.py --build $(BUILD_DIR)

docs: deps build
	$(PYTHON) scripts/gen_docs.py --build $(BUILD_DIR)

fuzz: deps
	JOBS=$(JOBS) bash scripts/fuzz.sh

install: deps build
	bash scripts/install-addon.sh

uninstall:
	bash scripts/install-addon.sh --uninstall

clean:
	rm -rf $(BUILD_DIR) build-fuzz $(OUT_DIR)
