#!/usr/bin/env bash
# End-to-end test of the packaged extension in a real VS Code: code-server (npm) with the .vsix
# installed, driven by headless Chromium through playwright-core (e2e/run.mjs).
#
#   PLX_SERVER_PATH=/path/to/venv/bin/plx bash vscode-extension/scripts/e2e.sh
#
# Needs Node 20 (code-server 4.100 requires it), the npm registry, a C/C++ toolchain and the Node
# headers for code-server's native modules (Debian: build-essential, libkrb5-dev, libx11-dev,
# libxkbfile-dev, nodejs' headers in /usr/include/node), ripgrep (/usr/bin/rg) and chromium
# (/usr/bin/chromium). Nothing else from the network: the browser and ripgrep come from Debian.
#
# PLX_SERVER_PATH  the plx the extension must find (default: plx on PATH). code-server is started
#                  with its folder first on PATH and openplx.server.path unset, so the test also
#                  checks discovery; E2E_SERVER_SETTING=1 sets openplx.server.path instead.
# E2E_VSIX         an already built .vsix (default: build one with npm ci + npm run package).
# E2E_CHROMIUM     the browser (default /usr/bin/chromium).
# E2E_KEEP=1       keep the temporary folder (workspace, code-server data and logs) after a pass.
#
# Installs go to vscode-extension/e2e/node_modules (ignored by git; reinstalled only when
# e2e/package-lock.json changes); everything else to a temporary folder that is removed after a pass
# and kept (with a screenshot) after a failure. Prints the time of each phase.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# absolute path of a file given relative to the caller's directory
absolute() { (cd "$(dirname "$1")" && printf '%s/%s' "$(pwd)" "$(basename "$1")"); }
export npm_config_update_notifier=false npm_config_fund=false npm_config_audit=false
started=$SECONDS
phase() { printf '\n== e2e: %s (%ss)\n' "$*" "$((SECONDS - started))"; }
die() { echo "e2e: error: $*" >&2; exit 2; }

plx="${PLX_SERVER_PATH:-$(command -v plx || true)}"
[[ -n "$plx" ]] || die "no plx: set PLX_SERVER_PATH or put plx on PATH"
plx="$(absolute "$plx")"
[[ -x "$plx" ]] || die "PLX_SERVER_PATH=$plx is not an executable"
chromium="${E2E_CHROMIUM:-/usr/bin/chromium}"
[[ -x "$chromium" ]] || die "no browser at $chromium (Debian: apt-get install chromium; or set E2E_CHROMIUM)"
[[ "$(node --version)" == v20.* ]] || die "code-server 4.100 needs Node 20, this is node $(node --version)"

if [[ -n "${E2E_VSIX:-}" ]]; then
  [[ -f "$E2E_VSIX" ]] || die "E2E_VSIX=$E2E_VSIX does not exist"
  vsix="$(absolute "$E2E_VSIX")"
else
  cd "$here"
  phase "build the .vsix (npm ci, npm run package)"
  npm ci --prefer-offline --no-audit --no-fund --loglevel=error
  npm run --silent package
  vsix="$here/openplx-vscode.vsix"
fi

phase "install code-server and playwright-core (e2e/)"
cd "$here/e2e"
stamp="node_modules/.e2e-lock-$(sha256sum package-lock.json | cut -c1-16)"
if [[ -f "$stamp" && -x node_modules/.bin/code-server ]]; then
  echo "up to date ($stamp)"
else
  # code-server's install script refuses to run as root without this (npm 9+ ignores the option
  # itself but passes it on); node-pty's install script runs `npx node-gyp`.
  export npm_config_unsafe_perm=true npm_config_yes=true
  # Build native modules against the installed Node headers instead of downloading them.
  if [[ -z "${npm_config_nodedir:-}" && -f /usr/include/node/node_version.h ]] && ! npm config get nodedir 2>/dev/null | grep -q /; then
    export npm_config_nodedir=/usr
  fi
  # @vscode/ripgrep downloads rg from GitHub unless its cache holds the archive: put the system rg there.
  rg_version="$(node -p "require('./package-lock.json').packages['node_modules/@vscode/ripgrep']?.version ?? ''" 2>/dev/null || true)"
  rg_cache="$(node -p 'require("os").tmpdir()')/vscode-ripgrep-cache-${rg_version:-1.15.11}"
  rg_archive="$rg_cache/ripgrep-v13.0.0-10-x86_64-unknown-linux-musl.tar.gz"
  if [[ ! -f "$rg_archive" ]]; then
    command -v rg >/dev/null || die "no ripgrep (Debian: apt-get install ripgrep)"
    mkdir -p "$rg_cache"
    rg_tmp="$(mktemp -d)"
    cp "$(command -v rg)" "$rg_tmp/rg"
    tar czf "$rg_archive" -C "$rg_tmp" rg
    rm -rf "$rg_tmp"
  fi
  rm -f node_modules/.e2e-lock-*
  npm ci --prefer-offline --no-audit --no-fund --loglevel=error >"${TMPDIR:-/tmp}/openplx-e2e-npm-ci.log" 2>&1 ||
    { tail -40 "${TMPDIR:-/tmp}/openplx-e2e-npm-ci.log"; die "npm ci in e2e/ failed (full log: ${TMPDIR:-/tmp}/openplx-e2e-npm-ci.log)"; }
  touch "$stamp"
fi
code_server="$here/e2e/node_modules/.bin/code-server"

phase "install the .vsix into a fresh code-server"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/openplx-e2e.XXXXXX")"
server_pid=""
cleanup() {
  local rc=$?
  if [[ -n "$server_pid" ]]; then
    kill "$server_pid" 2>/dev/null || true
    wait "$server_pid" 2>/dev/null || true
  fi
  if [[ $rc -ne 0 || "${E2E_KEEP:-}" == "1" ]]; then
    echo "e2e: kept $tmp (code-server log: $tmp/code-server.log, logs: $tmp/data/logs, screenshots: $tmp/artifacts)" >&2
  else
    rm -rf "$tmp"
  fi
}
trap cleanup EXIT
mkdir -p "$tmp"/{workspace,data/User,extensions,xdg-data,xdg-config,artifacts}
# code-server keeps a heartbeat and its own logs under XDG_DATA_HOME, its config under XDG_CONFIG_HOME.
export XDG_DATA_HOME="$tmp/xdg-data" XDG_CONFIG_HOME="$tmp/xdg-config"
export PLX_CACHE_DIR="${PLX_CACHE_DIR:-$tmp/plx-cache}"
"$code_server" --user-data-dir "$tmp/data" --extensions-dir "$tmp/extensions" \
  --install-extension "$vsix" --force
ls "$tmp/extensions" | grep -q '^plxtools\.openplx-vscode-' || die "the extension is not installed in $tmp/extensions"

cat >"$tmp/workspace/scene.openplx" <<'EOF'
# a scene for the end-to-end test
Scene is Physics3D.System:
    chassis is Physics3D.Bodies.RigidBody:
        inertia.mass: 10
EOF
# the 3D preview step draws the BoxTruck example
cp "$here/../examples/boxtruck/boxtruck.openplx" "$tmp/workspace/truck.openplx"
server_setting=""
if [[ "${E2E_SERVER_SETTING:-}" == "1" ]]; then
  server_setting="\"openplx.server.path\": \"$plx\","
fi
cat >"$tmp/data/User/settings.json" <<EOF
{
  $server_setting
  "workbench.startupEditor": "none",
  "workbench.colorTheme": "Default Dark Modern",
  "workbench.tips.enabled": false,
  "telemetry.telemetryLevel": "off",
  "update.mode": "none",
  "extensions.autoCheckUpdates": false,
  "extensions.autoUpdate": false,
  "workbench.enableExperiments": false,
  "security.workspace.trust.enabled": false,
  "editor.semanticHighlighting.enabled": false,
  "editor.inlayHints.enabled": "off",
  "editor.quickSuggestions": { "other": false, "comments": false, "strings": false },
  "editor.suggestOnTriggerCharacters": false,
  "editor.acceptSuggestionOnEnter": "off",
  "files.autoSave": "off"
}
EOF
port="$(node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})')"
printf 'bind-addr: 127.0.0.1:%s\nauth: none\ncert: false\n' "$port" >"$tmp/config.yaml"

phase "start code-server on 127.0.0.1:$port (PATH starts with $(dirname "$plx"))"
(
  cd "$tmp"
  export PATH="$(dirname "$plx"):$PATH"
  exec "$code_server" --config "$tmp/config.yaml" --user-data-dir "$tmp/data" --extensions-dir "$tmp/extensions" \
    --disable-telemetry --disable-update-check --disable-workspace-trust --disable-getting-started-override \
    "$tmp/workspace"
) >"$tmp/code-server.log" 2>&1 &
server_pid=$!
for _ in $(seq 1 120); do
  if node -e 'fetch(process.argv[1]).then(r=>process.exit(r.ok?0:1),()=>process.exit(1))' "http://127.0.0.1:$port/healthz" 2>/dev/null; then
    break
  fi
  kill -0 "$server_pid" 2>/dev/null || { cat "$tmp/code-server.log"; die "code-server exited"; }
  sleep 0.5
done

phase "drive it in headless Chromium (e2e/run.mjs)"
E2E_URL="http://127.0.0.1:$port" E2E_WORKSPACE="$tmp/workspace" E2E_LOGS="$tmp/data/logs" E2E_PLX="$plx" \
  E2E_ARTIFACTS="$tmp/artifacts" E2E_CHROMIUM="$chromium" node "$here/e2e/run.mjs"

phase "done"
