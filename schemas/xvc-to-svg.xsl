<?xml version="1.0" encoding="UTF-8"?>
<!--
  xvc-to-svg.xsl: draws the patterns of an XVC document as SVG (XSLT 1.0 + EXSLT
  common/math, as xsltproc and libxslt provide).

    xsltproc -o garment.svg schemas/xvc-to-svg.xsl garment.xvc

  Parameters (xsltproc's stringparam option, or vgd svg's layout and scale options):
  layout (rows | row | own) and scale (SVG user units per metre).

  Each PATTERN becomes <g class="pattern" id="PATTERN id"> holding
    path.outline     the boundary (its C2DSEQs concatenated), closed unless closed="false"
    path.internal / path.cutout / path.sew   the other lines
    line.grain (with an arrow), line.mirror, line.grade
    line.notch       from the notch along its angle, its length (or 4 mm when unstated)
    circle.drill     drill holes
    text.label       "piece size"
  Units: 1 SVG user unit = 1/scale metre (scale 1000: millimetres). Pattern y points up,
  SVG y points down, so y is flipped. layout=rows (default) gives each piece a row
  with its sizes side by side, rows in order of first appearance; layout=row puts all
  patterns side by side in document order; layout=own keeps their own coordinates.

  Numbers: vgd writes the shortest round-trip form, which may use an exponent ("5e-04").
  XPath 1.0 cannot read exponents, so the document is first copied with every
  coordinate converted to plain decimal user units ("norm" mode), then drawn from that.
-->
<xsl:stylesheet version="1.0"
    xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:exsl="http://exslt.org/common"
    xmlns:math="http://exslt.org/math"
    xmlns="http://www.w3.org/2000/svg"
    exclude-result-prefixes="exsl math">

  <xsl:output method="xml" indent="yes" encoding="UTF-8"/>

  <xsl:param name="scale" select="1000"/>     <!-- user units per metre -->
  <xsl:param name="layout" select="'rows'"/>  <!-- rows | row | own -->
  <xsl:param name="gap" select="30"/>         <!-- user units between patterns and rows -->
  <xsl:param name="margin" select="20"/>      <!-- user units around the drawing -->
  <xsl:param name="label-space" select="16"/> <!-- user units below a pattern for its label -->

  <!-- ============ pass 1: plain decimal user units ============ -->

  <!-- A number as written by vgd (maybe "1.5e-05", "+2E+3") times `factor`, as plain
       decimal text. format-number never writes an exponent, so the result reads back. -->
  <xsl:template name="decimal">
    <xsl:param name="s"/>
    <xsl:param name="factor" select="1"/>
    <xsl:variable name="t" select="translate(normalize-space($s), 'E+', 'e')"/>
    <xsl:choose>
      <xsl:when test="contains($t, 'e')">
        <xsl:value-of select="format-number(number(substring-before($t, 'e')) * $factor * math:power(10, number(substring-after($t, 'e'))), '0.######')"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:value-of select="format-number(number($t) * $factor, '0.######')"/>
      </xsl:otherwise>
    </xsl:choose>
  </xsl:template>

  <xsl:template match="@x | @y | @length | @width" mode="norm">
    <xsl:attribute name="{name()}">
      <xsl:call-template name="decimal">
        <xsl:with-param name="s" select="."/>
        <xsl:with-param name="factor" select="$scale"/>
      </xsl:call-template>
    </xsl:attribute>
  </xsl:template>
  <xsl:template match="@angle" mode="norm">
    <xsl:attribute name="angle">
      <xsl:call-template name="decimal">
        <xsl:with-param name="s" select="."/>
      </xsl:call-template>
    </xsl:attribute>
  </xsl:template>
  <xsl:template match="@*" mode="norm">
    <xsl:copy/>
  </xsl:template>
  <xsl:template match="*" mode="norm">
    <xsl:copy>
      <xsl:apply-templates select="@* | *" mode="norm"/>
    </xsl:copy>
  </xsl:template>

  <!-- ============ pass 2: layout and drawing ============ -->

  <xsl:template match="/">
    <xsl:variable name="norm-rtf">
      <xsl:apply-templates select="GARMENT" mode="norm"/>
    </xsl:variable>
    <xsl:variable name="g" select="exsl:node-set($norm-rtf)/GARMENT"/>

    <!-- One box per pattern: its extent. (Helper elements like this one are in the SVG
         namespace, so XPath below reaches them with * rather than by name.) -->
    <xsl:variable name="boxes-rtf">
      <xsl:for-each select="$g/PATTERNS/PATTERN">
        <xsl:variable name="xs" select="C2DSEQ/C2D/@x | POSITION/@x"/>
        <xsl:variable name="ys" select="C2DSEQ/C2D/@y | POSITION/@y"/>
        <box id="{@id}" piece="{@piece}">
          <xsl:choose>
            <xsl:when test="count($xs) &gt; 0">
              <xsl:attribute name="minx"><xsl:value-of select="math:min($xs)"/></xsl:attribute>
              <xsl:attribute name="maxx"><xsl:value-of select="math:max($xs)"/></xsl:attribute>
              <xsl:attribute name="miny"><xsl:value-of select="math:min($ys)"/></xsl:attribute>
              <xsl:attribute name="maxy"><xsl:value-of select="math:max($ys)"/></xsl:attribute>
            </xsl:when>
            <xsl:otherwise>
              <xsl:attribute name="minx">0</xsl:attribute>
              <xsl:attribute name="maxx">0</xsl:attribute>
              <xsl:attribute name="miny">0</xsl:attribute>
              <xsl:attribute name="maxy">0</xsl:attribute>
            </xsl:otherwise>
          </xsl:choose>
        </box>
      </xsl:for-each>
    </xsl:variable>
    <xsl:variable name="boxes" select="exsl:node-set($boxes-rtf)/*"/>

    <!-- layout=rows: one row per piece name, in order of first appearance. -->
    <xsl:variable name="rows-rtf">
      <xsl:for-each select="$boxes[not(@piece = preceding-sibling::*/@piece)]">
        <xsl:variable name="members" select="$boxes[@piece = current()/@piece]"/>
        <row piece="{@piece}" w="{sum($members/@maxx) - sum($members/@minx) + $gap * (count($members) - 1)}">
          <xsl:attribute name="h">
            <xsl:for-each select="$members">
              <xsl:sort select="@maxy - @miny" data-type="number" order="descending"/>
              <xsl:if test="position() = 1"><xsl:value-of select="@maxy - @miny"/></xsl:if>
            </xsl:for-each>
          </xsl:attribute>
        </row>
      </xsl:for-each>
    </xsl:variable>
    <xsl:variable name="rows" select="exsl:node-set($rows-rtf)/*"/>

    <!-- Extent of the whole drawing. -->
    <xsl:variable name="gminx" select="math:min($boxes/@minx)"/>
    <xsl:variable name="gmaxx" select="math:max($boxes/@maxx)"/>
    <xsl:variable name="gminy" select="math:min($boxes/@miny)"/>
    <xsl:variable name="gmaxy" select="math:max($boxes/@maxy)"/>
    <xsl:variable name="row-width">
      <xsl:choose>
        <xsl:when test="count($boxes) = 0">0</xsl:when>
        <xsl:otherwise>
          <xsl:value-of select="sum($boxes/@maxx) - sum($boxes/@minx) + $gap * (count($boxes) - 1)"/>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="row-height">
      <xsl:choose>
        <xsl:when test="count($boxes) = 0">0</xsl:when>
        <xsl:otherwise>
          <xsl:for-each select="$boxes">
            <xsl:sort select="@maxy - @miny" data-type="number" order="descending"/>
            <xsl:if test="position() = 1"><xsl:value-of select="@maxy - @miny"/></xsl:if>
          </xsl:for-each>
        </xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="inner-w">
      <xsl:choose>
        <xsl:when test="count($boxes) = 0">0</xsl:when>
        <xsl:when test="$layout = 'own'"><xsl:value-of select="$gmaxx - $gminx"/></xsl:when>
        <xsl:when test="$layout = 'rows'"><xsl:value-of select="math:max($rows/@w)"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="$row-width"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="inner-h">
      <xsl:choose>
        <xsl:when test="count($boxes) = 0">0</xsl:when>
        <xsl:when test="$layout = 'own'"><xsl:value-of select="$gmaxy - $gminy"/></xsl:when>
        <!-- every row but the last also has its label space and a gap below it -->
        <xsl:when test="$layout = 'rows'">
          <xsl:value-of select="sum($rows/@h) + (count($rows) - 1) * ($label-space + $gap)"/>
        </xsl:when>
        <xsl:otherwise><xsl:value-of select="$row-height"/></xsl:otherwise>
      </xsl:choose>
    </xsl:variable>
    <xsl:variable name="W" select="format-number($inner-w + 2 * $margin, '0.###')"/>
    <xsl:variable name="H" select="format-number($inner-h + 2 * $margin + $label-space, '0.###')"/>

    <svg version="1.1" width="{format-number($W * 1000 div $scale, '0.###')}mm"
         height="{format-number($H * 1000 div $scale, '0.###')}mm" viewBox="0 0 {$W} {$H}">
      <title><xsl:value-of select="$g/@name"/></title>
      <desc>XVC document <xsl:value-of select="$g/@id"/>: <xsl:value-of select="count($boxes)"/> patterns, 1 unit = <xsl:value-of select="1 div $scale"/> m</desc>
      <style>
        .outline { fill: #f6f1e7; stroke: #222; stroke-width: 0.6 }
        .internal, .sew { fill: none; stroke: #555; stroke-width: 0.3; stroke-dasharray: 3 2 }
        .cutout { fill: #fff; stroke: #222; stroke-width: 0.4 }
        .grain { stroke: #1a5fb4; stroke-width: 0.5 }
        .mirror { stroke: #a51d2d; stroke-width: 0.4; stroke-dasharray: 6 2 1 2 }
        .grade { stroke: #999; stroke-width: 0.3 }
        .notch { stroke: #c01c28; stroke-width: 0.6 }
        .drill { fill: #222 }
        .label { font-family: sans-serif; font-size: 6px; fill: #222; text-anchor: middle }
      </style>
      <defs>
        <marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="6" markerHeight="6" orient="auto">
          <path d="M 0 0 L 10 5 L 0 10 z" fill="#1a5fb4"/>
        </marker>
      </defs>
      <xsl:for-each select="$g/PATTERNS/PATTERN">
        <xsl:variable name="i" select="position()"/>
        <xsl:variable name="box" select="$boxes[$i]"/>
        <!-- X = x + dx, Y = dy - y -->
        <xsl:variable name="same-piece-before" select="$box/preceding-sibling::*[@piece = $box/@piece]"/>
        <xsl:variable name="row" select="$rows[@piece = $box/@piece]"/>
        <xsl:variable name="dx">
          <xsl:choose>
            <xsl:when test="$layout = 'own'"><xsl:value-of select="$margin - $gminx"/></xsl:when>
            <xsl:when test="$layout = 'rows'">
              <xsl:value-of select="$margin + sum($same-piece-before/@maxx) - sum($same-piece-before/@minx) + $gap * count($same-piece-before) - $box/@minx"/>
            </xsl:when>
            <xsl:otherwise>
              <xsl:value-of select="$margin + sum($boxes[position() &lt; $i]/@maxx) - sum($boxes[position() &lt; $i]/@minx) + $gap * ($i - 1) - $box/@minx"/>
            </xsl:otherwise>
          </xsl:choose>
        </xsl:variable>
        <xsl:variable name="dy">
          <xsl:choose>
            <xsl:when test="$layout = 'own'"><xsl:value-of select="$margin + $gmaxy"/></xsl:when>
            <xsl:when test="$layout = 'rows'">
              <xsl:value-of select="$margin + sum($row/preceding-sibling::*/@h) + count($row/preceding-sibling::*) * ($label-space + $gap) + $box/@maxy"/>
            </xsl:when>
            <xsl:otherwise><xsl:value-of select="$margin + $box/@maxy"/></xsl:otherwise>
          </xsl:choose>
        </xsl:variable>
        <xsl:call-template name="pattern">
          <xsl:with-param name="dx" select="number($dx)"/>
          <xsl:with-param name="dy" select="number($dy)"/>
          <xsl:with-param name="box" select="$box"/>
        </xsl:call-template>
      </xsl:for-each>
    </svg>
  </xsl:template>

  <!-- Coordinates of one point in SVG user units. -->
  <xsl:template name="xy">
    <xsl:param name="dx"/>
    <xsl:param name="dy"/>
    <xsl:value-of select="format-number(@x + $dx, '0.###')"/>
    <xsl:text> </xsl:text>
    <xsl:value-of select="format-number($dy - @y, '0.###')"/>
  </xsl:template>

  <!-- "M x y L x y ... [Z]" for a sequence of C2D. -->
  <xsl:template name="path-data">
    <xsl:param name="points"/>
    <xsl:param name="closed"/>
    <xsl:param name="dx"/>
    <xsl:param name="dy"/>
    <xsl:for-each select="$points">
      <xsl:choose>
        <xsl:when test="position() = 1">M </xsl:when>
        <xsl:otherwise> L </xsl:otherwise>
      </xsl:choose>
      <xsl:call-template name="xy">
        <xsl:with-param name="dx" select="$dx"/>
        <xsl:with-param name="dy" select="$dy"/>
      </xsl:call-template>
    </xsl:for-each>
    <xsl:if test="$closed and count($points) &gt; 0"> Z</xsl:if>
  </xsl:template>

  <xsl:template name="pattern">
    <xsl:param name="dx"/>
    <xsl:param name="dy"/>
    <xsl:param name="box"/>
    <g class="pattern" id="{@id}">
      <title><xsl:value-of select="concat(@id, ': block ', @block, ', piece ', @piece, ', size ', @size)"/></title>
      <!-- The outline: boundary stretches in document order. -->
      <path class="outline">
        <xsl:attribute name="d">
          <xsl:call-template name="path-data">
            <xsl:with-param name="points" select="C2DSEQ[not(@role) or @role = 'boundary']/C2D"/>
            <xsl:with-param name="closed" select="not(@closed = 'false' or @closed = '0')"/>
            <xsl:with-param name="dx" select="$dx"/>
            <xsl:with-param name="dy" select="$dy"/>
          </xsl:call-template>
        </xsl:attribute>
      </path>
      <!-- Cut-outs, internal and sew lines. -->
      <xsl:for-each select="C2DSEQ[@role = 'cutout' or @role = 'internal' or @role = 'sew'][C2D]">
        <path class="{@role}">
          <xsl:attribute name="d">
            <xsl:call-template name="path-data">
              <xsl:with-param name="points" select="C2D"/>
              <xsl:with-param name="closed" select="@closed = 'true' or @closed = '1'"/>
              <xsl:with-param name="dx" select="$dx"/>
              <xsl:with-param name="dy" select="$dy"/>
            </xsl:call-template>
          </xsl:attribute>
        </path>
      </xsl:for-each>
      <!-- Grain, mirror and grade lines: two points each. -->
      <xsl:for-each select="C2DSEQ[@role = 'grain' or @role = 'mirror' or @role = 'grade'][count(C2D) = 2]">
        <line class="{@role}" x1="{format-number(C2D[1]/@x + $dx, '0.###')}" y1="{format-number($dy - C2D[1]/@y, '0.###')}"
              x2="{format-number(C2D[2]/@x + $dx, '0.###')}" y2="{format-number($dy - C2D[2]/@y, '0.###')}">
          <xsl:if test="@role = 'grain'">
            <xsl:attribute name="marker-end">url(#arrow)</xsl:attribute>
          </xsl:if>
        </line>
      </xsl:for-each>
      <!-- Notches: a short cut along the notch's angle (y flips, so sin changes sign). -->
      <xsl:for-each select="POSITION[@type = 'notch']">
        <xsl:variable name="len">
          <xsl:choose>
            <xsl:when test="@length &gt; 0"><xsl:value-of select="@length"/></xsl:when>
            <xsl:otherwise><xsl:value-of select="0.004 * $scale"/></xsl:otherwise>
          </xsl:choose>
        </xsl:variable>
        <xsl:variable name="a">
          <xsl:choose>
            <xsl:when test="@angle"><xsl:value-of select="@angle * 3.14159265358979 div 180"/></xsl:when>
            <xsl:otherwise>0</xsl:otherwise>
          </xsl:choose>
        </xsl:variable>
        <line class="notch" x1="{format-number(@x + $dx, '0.###')}" y1="{format-number($dy - @y, '0.###')}"
              x2="{format-number(@x + $dx + $len * math:cos($a), '0.###')}"
              y2="{format-number($dy - @y - $len * math:sin($a), '0.###')}"/>
      </xsl:for-each>
      <xsl:for-each select="POSITION[@type = 'drill']">
        <circle class="drill" cx="{format-number(@x + $dx, '0.###')}" cy="{format-number($dy - @y, '0.###')}"
                r="{format-number(0.0015 * $scale, '0.###')}"/>
      </xsl:for-each>
      <!-- The label, centred under the pattern. -->
      <text class="label" x="{format-number(($box/@minx + $box/@maxx) div 2 + $dx, '0.###')}"
            y="{format-number($dy - $box/@miny + $label-space * 0.6, '0.###')}">
        <xsl:value-of select="normalize-space(concat(@piece, ' ', @size))"/>
      </text>
    </g>
  </xsl:template>
</xsl:stylesheet>
