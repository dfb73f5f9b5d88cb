# Every target sets up what it needs: a fresh clone needs only `make test` or `make serve`.
SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
# franka-sim (a simulated FR3 behind libfranka's protocol) pins numpy 1.26 and mujoco < 3.3: it
# gets a venv of its own, which runs only `python -m services.franka_sim`.
FRANKA_VENV := .venv-franka
FRANKA_SIM := franka-sim==1.1.7
BUF := node_modules/.bin/buf
PROTOS := $(wildcard protos/telerobot/v1/*.proto)
GEN_OUT ?= gen
export MUJOCO_GL ?= egl

.PHONY: install gen web lint docs test test-fast serve teleop bench certs clean c-observer

install: $(VENV)/.installed node_modules/.installed web/node_modules/.installed $(FRANKA_VENV)/.installed

# The virtual environment, with the project installed editable (services, clients, gen).
$(VENV)/.installed: pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[dev]'
	# matplotlib finds the system's fonts (fc-list) once, on first import; here, so that no
	# unit test starts that process
	$(PY) -c "import matplotlib.font_manager"
	touch $@

$(FRANKA_VENV)/.installed:
	test -x $(FRANKA_VENV)/bin/python || $(PYTHON) -m venv $(FRANKA_VENV)
	$(FRANKA_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(FRANKA_VENV)/bin/python -m pip install --quiet '$(FRANKA_SIM)'
	touch $@

# buf (lint, curl) and the Node.js client's packages, as locked. Not `npm ci`: the lock holds
# only the platform binaries of buf this registry serves, and `npm ci` wants every platform's.
node_modules/.installed: package.json package-lock.json
	npm install --no-audit --no-fund --loglevel=error
	touch $@

# The web console's build tools (buf, protoc-gen-es, TypeScript, esbuild), as locked in web/.
web/node_modules/.installed: web/package.json web/package-lock.json
	cd web && npm install --no-audit --no-fund --loglevel=error
	touch $@

# Rebuild the web console's page: its types from protos/ (buf generate, protoc-gen-es), a type
# check, and the bundle in services/web_console/static/app.js (committed, so `make serve`
# needs no npm; tests/web_console fails when it is stale).
web: web/node_modules/.installed
	cd web && npm run build --silent

# The C observer (clients/c): zenoh-pico and Mbed TLS (third_party/), the protos' C code from
# protoc-c.
C_OBSERVER := build/c-observer/telerobot-observe
c-observer: $(C_OBSERVER)
$(C_OBSERVER): $(VENV)/.installed /usr/bin/protoc-c clients/c/observe.c clients/c/CMakeLists.txt $(PROTOS)
	cmake -S clients/c -B build/c-observer -DCMAKE_BUILD_TYPE=Release -DWKT_DIR=$$($(PY) -c \
		"import grpc_tools, os; print(os.path.join(os.path.dirname(grpc_tools.__file__), '_proto'))") >/dev/null
	cmake --build build/c-observer -j2

/usr/bin/protoc-c:
	apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq cmake gcc \
		protobuf-c-compiler libprotobuf-c-dev pkg-config

# The web console's browser tests drive Debian's chromium (Playwright cannot download its own).
/usr/bin/chromium:
	apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium

# Regenerate the Python code and .pyi stubs from protos/ into $(GEN_OUT) (default gen/).
gen: $(VENV)/.installed
	rm -rf $(GEN_OUT)/telerobot
	mkdir -p $(GEN_OUT)
	$(PY) -m grpc_tools.protoc -Iprotos --python_out=$(GEN_OUT) --pyi_out=$(GEN_OUT) \
		--grpc_python_out=$(GEN_OUT) $(PROTOS)
	touch $(GEN_OUT)/telerobot/__init__.py $(GEN_OUT)/telerobot/v1/__init__.py

lint: install
	$(BUF) lint
	$(PY) -m ruff check discovery domain wire services clients tests bench

# The docs site (mkdocs.yml, docs/) into site/; --strict fails on a broken link or a page
# missing from the navigation.
docs: $(VENV)/.installed
	NO_MKDOCS_2_WARNING=1 $(PY) -m mkdocs build --strict

# Everything: the docs site, then every test (the end-to-end ones start real processes).
test: install /usr/bin/chromium docs $(C_OBSERVER)
	$(PY) -m pytest $(PYTEST_ARGS)

# Every test that starts no process (tests/conftest.py refuses one), in about a minute.
test-fast: $(VENV)/.installed
	$(PY) -m pytest -m "not e2e" $(PYTEST_ARGS)

# The slave station: every service in its own process, until Ctrl-C. ARM=fr3|ur5e|puma560;
# DRIVER=franka ROBOT_HOST=… drives a Franka (ARM=fr3), DRIVER=franka-sim franka-sim as one.
serve: $(VENV)/.installed
	$(PY) -m services.launcher $(if $(ARM),--arm $(ARM)) $(if $(DRIVER),--driver $(DRIVER)) $(if $(ROBOT_HOST),--robot-host $(ROBOT_HOST))

# A scripted peg-in-hole session, with and without server-side compliance; starts a local
# station if none answers (ARM and DRIVER as for serve). Artifacts land in runs/teleop-<time>/.
# EPISODES=N records N demonstration episodes at the station (TASK="..." labels them).
teleop: $(VENV)/.installed
	$(PY) -m clients.teleop $(if $(ARM),--arm $(ARM)) $(if $(DRIVER),--driver $(DRIVER)) \
		$(if $(EPISODES),--episodes $(EPISODES)) $(if $(TASK),--task "$(TASK)") $(TELEOP_ARGS)

# A development PKI in var/pki: a CA, a certificate per service and per identity (admin,
# operator, observer). HOSTS="name 10.0.0.2" adds names the servers answer on; FORCE=1 makes a
# new CA. Then: TELEROBOT_TLS_DIR=var/pki make serve (and the same for make teleop).
certs: $(VENV)/.installed
	$(PY) -m services.security.pki --dir var/pki $(foreach h,$(HOSTS),--host $(h)) \
		$(if $(filter-out 0,$(FORCE)),--force)

# ONLY="group ..." runs only those groups of bench/plan.py (e.g. ONLY=network, ONLY=soak:
# not in the default run, they take minutes).
bench: $(VENV)/.installed /usr/bin/chromium
	@test $(VENV)/.installed-bench -nt pyproject.toml || { \
		$(PY) -m pip install --quiet -e '.[dev,bench]' && touch $(VENV)/.installed-bench; }
	$(PY) -m bench $(if $(filter-out 0,$(QUICK)),--quick) $(if $(ONLY),--only $(ONLY))
	$(PY) -m bench.readme  # docs/performance.md's tables, from bench/results/latest.json

clean:
	rm -rf $(VENV) $(FRANKA_VENV) node_modules .pytest_cache .ruff_cache
