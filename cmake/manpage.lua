-- SPDX-License-Identifier: MIT
-- A pandoc filter that makes a man page of a page of docs/ (cmake/manpages.cmake):
--   pandoc --standalone --from=gfm --to=man --lua-filter=cmake/manpage.lua
--          -M program=apcictl -M summary="..." -M docdir=/usr/share/doc/apci-tools ... docs/apcictl.md
-- The page's title (# ...) becomes NAME ("apcictl - summary"); its first code block, the
-- usage lines, SYNOPSIS; the rest of its introduction DESCRIPTION. Each "## Heading" is a
-- section (.SH, in capitals), "### Heading" a subsection (.SS), deeper ones bold paragraphs.
-- The sections man(7) orders at the end go there, in its order: EXIT STATUS, ENVIRONMENT,
-- FILES, EXAMPLES, SEE ALSO; a page without the first four is an error. Paths "docs/NAME.md"
-- and links to NAME.md become the installed page, docdir/NAME.md; figures (images) are left
-- out, as man cannot show them, with their caption kept. A path may break after a "/".

local program, summary, docdir

local function meta_text(m, key)
  local v = m[key]
  if v == nil then
    error("manpage.lua: -M " .. key .. "=... is required")
  end
  return pandoc.utils.stringify(v)
end

local function installed(path)
  -- "docs/otc.md", "otc.md", "docs/otc.md#anchor" -> docdir/otc.md
  local name = path:match("^docs/([%w%-_]+%.md)") or path:match("^([%w%-_]+%.md)")
  if name then return docdir .. "/" .. name end
  return nil
end

local function rewrite_text(text)
  return (text:gsub("docs/([%w%-_]+%.md)", function(name) return docdir .. "/" .. name end))
end

local inline_filter = {
  Code = function(c)
    c.text = rewrite_text(c.text)
    return c
  end,
  Str = function(s)
    s.text = rewrite_text(s.text)
    -- The page is never hyphenated (cmake/manpages.cmake): a path may break after each "/"
    -- instead (\: is a break point that prints nothing), so a long one fits a table cell.
    if not s.text:find("/.") then return s end
    local parts = {}
    for piece in s.text:gmatch("[^/]*/?") do
      if piece ~= "" then
        table.insert(parts, pandoc.Str(piece))
        if piece:sub(-1) == "/" then table.insert(parts, pandoc.RawInline("man", "\\:")) end
      end
    end
    return parts
  end,
  Link = function(l)
    local target = installed(l.target)
    if target then l.target = target end
    return l
  end,
  Image = function(img)
    return pandoc.Emph(img.caption)
  end,
}

local kTail = { "EXIT STATUS", "ENVIRONMENT", "FILES", "EXAMPLES", "SEE ALSO" }
local kRequired = { ["EXIT STATUS"] = true, ENVIRONMENT = true, FILES = true, EXAMPLES = true }

function Pandoc(doc)
  program = meta_text(doc.meta, "program")
  summary = meta_text(doc.meta, "summary")
  docdir = meta_text(doc.meta, "docdir")
  doc = doc:walk(inline_filter)

  -- Split the blocks: the introduction (before the first "##"), then one list per section.
  local intro, sections, order = {}, {}, {}
  local current = nil
  for _, b in ipairs(doc.blocks) do
    if b.t == "Header" and b.level == 1 then
      -- The page's title: NAME comes from the metadata instead.
    elseif b.t == "Header" and b.level == 2 then
      local name = pandoc.utils.stringify(b.content):upper()
      current = { header = name, blocks = {} }
      sections[name] = current
      table.insert(order, current)
    elseif current == nil then
      table.insert(intro, b)
    else
      if b.t == "Header" then b.level = b.level - 1 end
      table.insert(current.blocks, b)
    end
  end

  local out = {}
  local function section(name, blocks)
    table.insert(out, pandoc.Header(1, name))
    for _, b in ipairs(blocks) do table.insert(out, b) end
  end
  section("NAME", { pandoc.Para({ pandoc.Str(program), pandoc.Space(), pandoc.Str("-"),
                                  pandoc.Space(), pandoc.Str(summary) }) })
  local synopsis, description = nil, {}
  for _, b in ipairs(intro) do
    if synopsis == nil and b.t == "CodeBlock" then
      synopsis = b
    else
      table.insert(description, b)
    end
  end
  if synopsis == nil then error("manpage.lua: the page has no usage block for SYNOPSIS") end
  section("SYNOPSIS", { synopsis })
  section("DESCRIPTION", description)
  local tail = {}
  for _, name in ipairs(kTail) do tail[name] = true end
  for _, s in ipairs(order) do
    if not tail[s.header] then section(s.header, s.blocks) end
  end
  for _, name in ipairs(kTail) do
    if sections[name] then
      section(name, sections[name].blocks)
    elseif kRequired[name] then
      error("manpage.lua: the page has no '## " .. name .. "' section (man-pages(7))")
    end
  end
  doc.blocks = out
  return doc
end
