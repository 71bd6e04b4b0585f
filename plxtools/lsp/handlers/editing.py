"""Completion (with lazily resolved documentation), signature help, formatting, and code
actions (quick fixes, "fix all", suppressions and "migrate this file")."""

from __future__ import annotations

import asyncio
import os
import time
from typing import TYPE_CHECKING

from lsprotocol import types

from plxtools import ide
from plxtools.ide import migrate_action
from plxtools.ide.runtime.collector import no_gc
from plxtools.lsp import completion_items
from plxtools.lsp.convert import Positions
from plxtools.lsp.protocol import RequestFailed
from plxtools.rules import registry
from plxtools.ide.signature import param_label_offsets

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer


def register(server, server_feature) -> None:
    @server_feature(types.TEXT_DOCUMENT_COMPLETION,
                    types.CompletionOptions(trigger_characters=[".", " "], resolve_provider=True))
    async def completion(ls: PlxServer, params: types.CompletionParams):
        if ls.warming is not None:
            # the bundles are loading (a fraction of a second from plx's cache): wait for them, then
            # answer from the buffer's parse and symbols without its check, which waits for this
            # answer. An empty list is no answer: Neovim does not ask again after one
            # (the first check waits until this answer is sent: transport.PROMPT)
            await asyncio.shield(ls.warming)
        t0, c0 = time.perf_counter(), time.process_time()
        ctx = params.context
        trigger = ctx.trigger_character if ctx is not None and ctx.trigger_kind == \
            types.CompletionTriggerKind.TriggerCharacter else None
        view = ls.line_view(params.text_document.uri, params.position.line)
        if view is not None:
            # typing on one line since the last analysis: answer from it and the line's text, at once
            st = view.state
            lp = Positions(view.text, ls.encoding)
            col = lp.offset_at(0, params.position.character)
            res = ide.complete_line(st, view.line, view.text, col, view.start, trigger, view.own_line,
                                    min(view.start + col, view.old_end))

            def at(offset: int) -> dict:
                return {"line": view.line, "character": lp.line_character(offset - view.start)[1]}
            rng = {"start": at(res.replace_start), "end": at(view.start + col)}
        else:
            with no_gc():
                st = ls.state(params.text_document.uri, quick=True)
            if st is None:
                return None
            pos = ls.positions(st.path, st)
            offset = pos.offset(params.position)
            res = ide.complete(st, offset, trigger)
            rng = completion_items.lsp_range(pos, res.replace_start, offset)
        ls._completion_keys = []
        answer = completion_items.completion_list(
            res, rng, _item_options(ls), ls._completion_keys,
            lambda key: ide.completion_documentation(st.program, key))
        ls.stats.record("completion" if st.checked and view is None else "completion-while-typing", t0, c0)
        return answer

    @server_feature(types.COMPLETION_ITEM_RESOLVE)
    def completion_resolve(ls: PlxServer, item: types.CompletionItem):
        data = item.data if isinstance(item.data, dict) else {}
        k = data.get("k")
        if isinstance(k, int) and 0 <= k < len(ls._completion_keys) and ls.host.program is not None:
            doc = ide.completion_documentation(ls.host.program, ls._completion_keys[k])
            if doc:
                item.documentation = ls.doc_markup(doc)
        return item

    @server_feature(types.TEXT_DOCUMENT_SIGNATURE_HELP,
                    types.SignatureHelpOptions(trigger_characters=["(", ","], retrigger_characters=[","]))
    def signature_help(ls: PlxServer, params: types.SignatureHelpParams):
        st = ls.state(params.text_document.uri, quick=True)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        res = ide.signature_help(st, pos.offset(params.position))
        if res is None:
            return None
        offsets = ls.cap("text_document.signature_help.signature_information.parameter_information."
                         "label_offset_support")

        sigs = []
        for s in res.signatures:
            labels = param_label_offsets(s) if offsets else [p.label for p in s.parameters]
            params_ = [types.ParameterInformation(label=lab) for lab in labels]
            # the active parameter inside each signature too: LSP 3.18 reads a null there as "none"
            active = min(res.active_parameter or 0, max(len(params_) - 1, 0))
            sigs.append(types.SignatureInformation(label=s.label, parameters=params_,
                                                   documentation=ls.doc_markup(s.documentation)
                                                   if s.documentation else None,
                                                   active_parameter=active))
        return types.SignatureHelp(signatures=sigs, active_signature=res.active_signature,
                                   active_parameter=res.active_parameter)


    @server_feature(types.TEXT_DOCUMENT_FORMATTING)
    def formatting(ls: PlxServer, params: types.DocumentFormattingParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        try:
            edits = ide.format_document(st.text, st.path if os.path.isabs(st.path) else "")
        except ide.FormattingRefused as exc:
            if exc.syntax:
                ls.window_log_message(types.LogMessageParams(type=types.MessageType.Info, message=f"plx: {exc}"))
                return []
            raise RequestFailed(str(exc)) from None
        pos = ls.positions(st.path, st)
        return [types.TextEdit(range=pos.offsets_range(e.start, e.end), new_text=e.text) for e in edits]

    @server_feature(types.TEXT_DOCUMENT_RANGE_FORMATTING)
    def range_formatting(ls: PlxServer, params: types.DocumentRangeFormattingParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        r = params.range
        end_line = r.end.line - 1 if r.end.character == 0 and r.end.line > r.start.line else r.end.line
        try:
            edits = ide.format_lines(st.text, r.start.line, end_line)
        except ide.FormattingRefused as exc:
            raise RequestFailed(str(exc)) from None
        pos = ls.positions(st.path, st)
        return [types.TextEdit(range=pos.offsets_range(e.start, e.end), new_text=e.text) for e in edits]

    # -------------------------------------------------------------- code actions

    @server_feature(types.TEXT_DOCUMENT_CODE_ACTION,
                    types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix,
                                                               types.CodeActionKind.SourceFixAll,
                                                               migrate_action.KIND]))
    def code_action(ls: PlxServer, params: types.CodeActionParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        start, end = pos.offset(params.range.start), pos.offset(params.range.end)
        only = [str(k.value if hasattr(k, "value") else k) for k in params.context.only] \
            if params.context.only else None
        sent = list(params.context.diagnostics or [])
        out = [_code_action(ls, st, pos, a, sent) for a in ide.code_actions(st, start, end, only)]
        migrate = _migrate_action(ls, st, only, sent)
        if migrate is not None:
            out.append(migrate)
        return out

    @server.command(migrate_action.FETCH_COMMAND)
    async def fetch_bundles(ls, *args):  # (no annotations: pygls reads them to convert the arguments)
        """Fetch an OpenPLX version's bundles (as `plx bundles install`), in a thread; then the
        migrate action offers the migration itself."""
        args = _arguments(args)
        version = args[0] if args and isinstance(args[0], str) else None
        if version is None:
            raise RequestFailed(f"{migrate_action.FETCH_COMMAND} needs a version, such as 0.17.26")
        from plxtools.model.versions import BundleSetError

        try:
            where = await asyncio.get_running_loop().run_in_executor(None, migrate_action.fetch_bundles, version)
        except BundleSetError as exc:
            ls.window_show_message(types.ShowMessageParams(
                type=types.MessageType.Error, message=f"plx: cannot fetch the bundles of OpenPLX {version}: {exc}"))
            return {"fetched": None, "error": str(exc)}
        ls.migrations.forget()
        ls.window_show_message(types.ShowMessageParams(
            type=types.MessageType.Info,
            message=f"plx: fetched the bundles of OpenPLX {version}; ask for code actions again to migrate"))
        return {"fetched": where}

    @server.command(migrate_action.EXPLAIN_COMMAND)
    def explain_refusal(ls, *args):
        """Why a migration is not possible (for clients that cannot show a disabled action's reason)."""
        args = _arguments(args)
        reason = args[0] if args else "refused"
        ls.window_show_message(types.ShowMessageParams(type=types.MessageType.Warning,
                                                       message=f"plx: cannot migrate this file: {reason}"))


def _arguments(args: tuple) -> list:
    """A command's arguments, whether pygls passed them spread out or as one list."""
    if len(args) == 1 and isinstance(args[0], (list, tuple)):
        return list(args[0])
    return list(args)


def _code_action(ls: PlxServer, st, pos, a, sent: list[types.Diagnostic]) -> types.CodeAction:
    """An ide.CodeAction in LSP terms; its diagnostics are the client's own objects where it sent them."""
    changes = {}
    for path, edits in a.edits.items():
        fp = ls.positions(path, st if path == st.path else None)
        changes[ls.uri_of(path)] = [types.TextEdit(range=fp.offsets_range(e.start, e.end), new_text=e.text)
                                    for e in edits]
    diags = []
    for d in a.diagnostics[:20]:
        rng = pos.range(d.span)
        match = next((x for x in sent if x.code == d.code and x.range == rng), None)
        diags.append(match or ls.lsp_diagnostic(d, pos))
    return types.CodeAction(title=a.title, kind=a.kind, diagnostics=diags or None,
                            is_preferred=a.preferred or None, edit=types.WorkspaceEdit(changes=changes))


def _migrate_action(ls: PlxServer, st, only, sent: list[types.Diagnostic]) -> types.CodeAction | None:
    """ "Migrate this file" (ide/migrate_action.py). Where the version diagnostic is (VS Code's Ctrl+.
    shows quick fixes, not source actions) it is also a quick fix of it; elsewhere a source action only."""
    version_diags = [x for x in sent if x.code in registry.tagged("version")]
    as_quickfix = bool(version_diags) and (only is None or any(k in ("quickfix", "") for k in only))
    m = ls.migrations.offer(ls.host, st, None if as_quickfix else only)
    if m is None:
        return None
    kind = types.CodeActionKind.QuickFix if as_quickfix else migrate_action.KIND
    if m.fetch is not None:  # the old version's bundles are missing: offer to fetch them
        return types.CodeAction(title=m.title, kind=kind, diagnostics=version_diags or None,
                                command=types.Command(title=m.title, command=migrate_action.FETCH_COMMAND,
                                                      arguments=[m.fetch]))
    if m.new_text is None:
        # always shown, with its reason in the title too: Neovim lists a disabled action as
        # "(disabled)" only, and a client without disabledSupport would hide it
        title = f"{m.title}: not possible, {m.reason or 'refused'}"
        if ls.cap("text_document.code_action.disabled_support"):
            return types.CodeAction(title=title, kind=kind,
                                    disabled=types.CodeActionDisabled(reason=m.reason or "refused"))
        return types.CodeAction(title=title, kind=kind, command=types.Command(
            title=title, command=migrate_action.EXPLAIN_COMMAND, arguments=[m.reason or "refused"]))
    pos = ls.positions(st.path, st)
    edit = types.WorkspaceEdit(changes={ls.uri_of(st.path): [
        types.TextEdit(range=pos.offsets_range(0, len(st.text)), new_text=m.new_text)]})
    if as_quickfix:
        return types.CodeAction(title=m.title, kind=types.CodeActionKind.QuickFix, diagnostics=version_diags,
                                edit=edit)
    return types.CodeAction(title=m.title, kind=migrate_action.KIND, edit=edit)


def _item_options(ls: PlxServer) -> completion_items.ItemOptions:
    base = "text_document.completion.completion_item."
    return completion_items.ItemOptions(
        lazy_documentation="documentation" in (ls.cap(base + "resolve_support.properties") or []),
        label_details=bool(ls.cap(base + "label_details_support")), tags=ls.cap(base + "tag_support") is not None,
        markdown=types.MarkupKind.Markdown in (ls.cap(base + "documentation_format") or []))

