# marsokhod — the two commands: `make test` and (once the simulator lands) `make run`.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
FUZZ_SECONDS ?= 150
SOAK_HOURS ?= 1
SOAK_SEED ?= 1
SWEEP_SEEDS ?= 1-20
CMAKE_FLAGS ?= -DMARSOKHOD_WERROR=ON

.PHONY: all deps configure build test bench fuzz run web soak sweep params-doc firmware clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

test: build web
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)
	@if [ -f web/package.json ]; then cd web && MARSOKHOD_BIN=$(abspath $(BUILD_DIR))/src/app/marsokhod npm test; fi

# The nine controllers' firmware (firmware/, docs/firmware.md): BUILD_DIR/firmware/mu0..mu8.elf
# and .hex with gcc-avr, and each image's flash and RAM use. `make build` builds them too.
firmware: deps
	$(MAKE) --no-print-directory -C firmware OUT=$(abspath $(BUILD_DIR))/firmware

bench: build
	@bash scripts/run-benchmarks.sh $(BUILD_DIR)

fuzz: deps
	@FUZZ_SECONDS=$(FUZZ_SECONDS) bash scripts/fuzz.sh

# Random operation with random faults, every invariant checked each cycle (RELIABILITY.md):
# SOAK_HOURS simulated hours (about 6 min of wall time per hour). A violation exits 1 and leaves
# its recording in soak-seed-SOAK_SEED/ (marsokhod replay soak-seed-SOAK_SEED).
soak: build
	$(BUILD_DIR)/src/app/marsokhod soak --hours $(SOAK_HOURS) --seed $(SOAK_SEED)

# Every shipped scenario on every seed of SWEEP_SEEDS (each seed a different rover unit), in
# parallel on all cores; the table of RELIABILITY.md.
sweep: build
	$(BUILD_DIR)/src/app/marsokhod scenario --all --seeds $(SWEEP_SEEDS)

# The console: npm packages from the lock file, then the Vite build into web/dist.
web: deps
	@if [ -f web/package.json ]; then cd web && npm ci --no-audit --no-fund && npm run build; \
	else echo "make web: no console sources (web/package.json) yet"; fi

# docs/parameters.md from the parameter schema (src/config/param_schema.cpp); a test fails while
# the page in the tree is stale.
params-doc: build
	$(BUILD_DIR)/src/config/marsokhod-param-docs > docs/parameters.md

# The simulated rover, the driver and the console in one process; open the printed URL.
run: build web
	$(BUILD_DIR)/src/app/marsokhod run --web web/dist

clean:
	rm -rf $(BUILD_DIR) build-fuzz
