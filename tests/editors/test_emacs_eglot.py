"""The Emacs set-up of docs/editors.md, run for real in the machine's Emacs (Debian 12: 28.2 with
eglot 1.9 from elpa-eglot) and in Emacs 30.1 from Debian 13 (eglot built in; unpacked by
`debian_editors.py`): the elisp block is taken from the page, loaded into `emacs --batch` with eglot, and used as a person would (open a model, read the diagnostics,
hover, jump to a bundle, complete, format). So the documented snippet is the tested one.

Needs `emacs` with eglot (Debian: emacs-nox, elpa-eglot); `.ci/run` installs them and sets
PLX_EDITOR_TESTS=1, which turns a missing editor into a failure instead of a skip.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.editors.common import REQUIRED, debian_editor, doc_blocks, make_project

# what a person does, in elisp; every answer is printed as `RESULT key: value`
DRIVE = r"""
(require 'eglot)
(load-file SNIPPET)
(defun plx-say (key value) (princ (format "RESULT %s: %s\n" key value)))
(defun plx-wait (pred secs)
  (let ((end (+ (float-time) secs)))
    (while (and (not (funcall pred)) (< (float-time) end))
      (accept-process-output nil 0.1))
    (funcall pred)))
(setq plx-opened (float-time))
(find-file MODEL)
(plx-say "mode" major-mode)
;; eglot-ensure connects after the first command; in batch there is none, so run the hook once
(run-hooks 'post-command-hook)
(plx-wait (lambda () (eglot-current-server)) 60)
(plx-say "connected" (if (eglot-current-server) "yes" "no"))
(plx-say "root" (expand-file-name (project-root (project-current))))
(plx-wait (lambda () (flymake-diagnostics)) 60)
(plx-say "first-diagnostics-seconds" (format "%.2f" (- (float-time) plx-opened)))
(dolist (d (flymake-diagnostics))
  (plx-say "diagnostic" (format "%d %s" (line-number-at-pos (flymake-diagnostic-beg d))
                                (car (split-string (flymake-diagnostic-text d) "\n")))))
(goto-char (point-min)) (search-forward "RigidBody") (backward-char 2)
(let ((hover (jsonrpc-request (eglot-current-server) :textDocument/hover
                              (eglot--TextDocumentPositionParams))))
  (plx-say "hover" (car (split-string (format "%s" (plist-get (plist-get hover :contents) :value)) "\n"))))
(call-interactively #'xref-find-definitions)
(plx-say "definition" (format "%s:%d" (buffer-file-name) (line-number-at-pos)))
(sit-for 1)
(plx-say "servers" (format "%d %s" (length (delete-dups (apply #'append (hash-table-values eglot--servers-by-project))))
                           (if (eglot-current-server) "managed" "unmanaged")))
(find-file MODEL)
(goto-char (point-min)) (search-forward "inertia.")
(plx-say "completion" (mapconcat #'identity (all-completions "" (nth 2 (eglot-completion-at-point))) " "))
(goto-char (point-min)) (insert "Extra:\n    a is Real:   1\n\n")
(eglot-format-buffer)
(plx-say "formatted" (replace-regexp-in-string "\n" "|" (buffer-substring (point-min) (+ (point-min) 42))))
(kill-emacs 0)
"""


def _emacs_with_eglot() -> str | None:
    emacs = shutil.which("emacs")
    if emacs is None:
        return None
    probe = subprocess.run([emacs, "--batch", "-q", "--eval", "(require 'eglot)"], capture_output=True, timeout=60)
    return emacs if probe.returncode == 0 else None


@pytest.mark.parametrize("setup", ["emacs-28-system", "emacs-30-trixie"])
def test_the_documented_emacs_setup_gives_diagnostics_hover_definition_completion_and_formatting(tmp_path, setup):
    if setup == "emacs-30-trixie":
        emacs = str(debian_editor("trixie", "emacs-nox"))  # Emacs 30, eglot built in
    else:
        emacs = _emacs_with_eglot()
        if emacs is None:
            if REQUIRED:
                pytest.fail("PLX_EDITOR_TESTS=1 but emacs with eglot is not installed")
            pytest.skip("emacs with eglot not installed (Debian: emacs-nox elpa-eglot)")
    version = subprocess.run([emacs, "--batch", "-q", "--eval", "(princ emacs-version)"], capture_output=True,
                             text=True, timeout=60).stdout
    assert version.startswith("30." if setup == "emacs-30-trixie" else ("28.", "29.", "30.", "31.")), version
    project = make_project(tmp_path)
    model = project / "model.openplx"
    (tmp_path / "snippet.el").write_text(doc_blocks("Emacs (eglot)", "elisp")[0], encoding="utf-8")
    drive = DRIVE.replace("SNIPPET", f'"{tmp_path / "snippet.el"}"').replace("MODEL", f'"{model}"')
    (tmp_path / "drive.el").write_text(drive, encoding="utf-8")
    env = dict(os.environ, HOME=str(tmp_path), PATH=str(Path(sys.executable).parent) + os.pathsep + os.environ["PATH"])
    r = subprocess.run([emacs, "--batch", "-q", "-l", str(tmp_path / "drive.el")], capture_output=True, text=True,
                       timeout=300, env=env, cwd=project)
    results: dict[str, list[str]] = {}
    for line in r.stdout.splitlines():
        if line.startswith("RESULT "):
            key, _, value = line[len("RESULT "):].partition(": ")
            results.setdefault(key, []).append(value)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert results["mode"] == ["openplx-mode"], out
    assert results["connected"] == ["yes"], out
    assert Path(results["root"][0]).resolve() == project.resolve(), out
    # issue 40.1: first diagnostics within 1.5 s warm / 4 s cold on a quiet machine (Emacs start and
    # eglot's connection included here); asserted loosely, the machine is shared
    print(f"{setup}: open to first diagnostics {results['first-diagnostics-seconds'][0]} s")
    assert float(results["first-diagnostics-seconds"][0]) < 30, out
    assert results["diagnostic"] == ["4 plx [N002]: 'raduis' is not an attribute of Physics3D.Geometries.Sphere"], out
    assert results["hover"][0].startswith("Physics3D.Bodies.RigidBody is Physics3D.Bodies.Body"), out
    assert results["definition"][0].replace(os.sep, "/").endswith("Physics3D/Bodies/RigidBody.openplx:1"), out
    # issue 32.11: the bundle file joined the running server (one server, and it manages the file)
    assert results["servers"] == ["1 managed"], out
    assert "mass" in results["completion"][0].split(), out
    assert results["formatted"] == ["Extra:|    a is Real: 1||Ball is Physics3D"], out
