-- What a person does in Neovim with the documented set-up, as a script: open a model, read the
-- diagnostic, hover (K), look at the signature help, complete, jump into a bundle (<C-]>), come back,
-- reload with :e! a few times, fix the typo and format. Every answer is written to $PLX_RESULTS as
-- `key: value` lines for the Python test to read.
local out = assert(io.open(vim.env.PLX_RESULTS, "w"))
local function say(key, value)
  out:write(key .. ": " .. (tostring(value):gsub("\n", "|")) .. "\n")
  out:flush()
end
local function pause(ms) vim.wait(ms, function() return false end, 20) end
local function clients() return vim.lsp.get_clients({ name = "plx" }) end
local function floats()
  local found = {}
  for _, win in ipairs(vim.api.nvim_list_wins()) do
    if vim.api.nvim_win_get_config(win).relative ~= "" then found[#found + 1] = win end
  end
  return found
end

local ok, err = pcall(function()
  vim.cmd.edit(vim.env.PLX_MODEL)
  local buf = vim.api.nvim_get_current_buf()
  say("filetype", vim.bo.filetype)
  vim.wait(60000, function() return #clients() > 0 and clients()[1].initialized end, 50)
  say("clients", #clients())
  say("root", clients()[1] and clients()[1].config.root_dir)
  vim.wait(60000, function() return #vim.diagnostic.get(buf) > 0 end, 50)
  for _, d in ipairs(vim.diagnostic.get(buf)) do
    say("diagnostic", (d.lnum + 1) .. " " .. tostring(d.code) .. " " .. d.message:match("[^\n]*"))
  end

  -- K on RigidBody: the hover float
  vim.fn.search("RigidBody")
  vim.lsp.buf.hover()
  vim.wait(10000, function() return #floats() > 0 end, 50)
  local float = floats()[1]
  say("hover", float and table.concat(vim.api.nvim_buf_get_lines(vim.api.nvim_win_get_buf(float), 0, 3, false), "\n"))
  for _, win in ipairs(floats()) do vim.api.nvim_win_close(win, true) end

  -- signature help on the second argument of from_xyz: which parameter Neovim highlights
  vim.fn.search("from_xyz(1, ", "w")
  vim.cmd("normal! f,l")
  local params = vim.lsp.util.make_position_params(0, clients()[1].offset_encoding)
  for _, r in pairs(vim.lsp.buf_request_sync(buf, "textDocument/signatureHelp", params, 10000) or {}) do
    if r.result then
      local lines, hl = vim.lsp.util.convert_signature_help_to_markdown_lines(r.result, "openplx", { "(", "," })
      local label = r.result.signatures[r.result.activeSignature and r.result.activeSignature + 1 or 1].label
      local marked = "none"
      if hl and #hl == 4 then -- 0.11 and later: {start line, start col, end line, end col} in `lines`
        marked = lines[hl[1] + 1]:sub(hl[2] + 1, hl[4])
      elseif hl then -- 0.10: byte offsets into the label
        marked = label:sub(hl[1] + 1, hl[2])
      end
      say("signature", label .. " => " .. marked)
    end
  end

  -- completion after `inertia.`
  vim.fn.search("inertia\\.", "w")
  vim.cmd("normal! f.")
  params = vim.lsp.util.make_position_params(0, clients()[1].offset_encoding)
  params.position.character = params.position.character + 1
  for _, r in pairs(vim.lsp.buf_request_sync(buf, "textDocument/completion", params, 10000) or {}) do
    local items = r.result and (r.result.items or r.result) or {}
    local labels = {}
    for _, item in ipairs(items) do labels[#labels + 1] = item.label end
    table.sort(labels)
    say("completion", table.concat(labels, " "))
  end

  -- <C-]> on RigidBody: into the official bundle, which must not start a second server
  vim.fn.search("RigidBody", "w")
  vim.cmd("normal! \29")
  vim.wait(10000, function() return vim.api.nvim_buf_get_name(0):match("RigidBody%.openplx$") ~= nil end, 50)
  say("definition", vim.api.nvim_buf_get_name(0) .. ":" .. vim.fn.line("."))
  pause(1500)
  say("clients after definition", #clients())
  say("bundle buffer attached", #vim.lsp.get_clients({ name = "plx", bufnr = 0 }))

  -- back to the model, reloaded five times
  vim.cmd.edit(vim.env.PLX_MODEL)
  for _ = 1, 5 do
    vim.cmd("edit!")
    pause(200)
  end
  pause(1500)
  say("clients after reloads", #clients())
  buf = vim.api.nvim_get_current_buf()
  say("model buffer attached", #vim.lsp.get_clients({ name = "plx", bufnr = buf }))

  -- fix the typo: the diagnostic goes away
  local typo = vim.fn.search("raduis", "w")
  vim.api.nvim_buf_set_lines(buf, typo - 1, typo, false, { "        radius: 0.5" })
  vim.wait(30000, function() return #vim.diagnostic.get(buf) == 0 end, 50)
  say("diagnostics after fix", #vim.diagnostic.get(buf))

  -- format the buffer
  vim.api.nvim_buf_set_lines(buf, 0, 0, false, { "Extra:", "    a is Real:   1", "" })
  vim.lsp.buf.format({ async = false, timeout_ms = 10000 })
  say("formatted", table.concat(vim.api.nvim_buf_get_lines(buf, 0, 4, false), "|"))
end)
if not ok then say("error", err) end
say("messages", vim.fn.execute("messages"))
out:close()
vim.cmd("qall!")
