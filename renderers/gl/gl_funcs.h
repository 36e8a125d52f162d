/* Every OpenGL function shadesweep calls, as an X-macro list:
 *
 *     GL_FUNC(return type, name without the "gl" prefix, (parameters))
 *
 * loader.h expands it into the members of struct gl_api (so code calls
 * gl.Clear(GL_COLOR_BUFFER_BIT)), and loader.c into the resolution of each entry
 * as "gl" + name through the backend's GetProcAddress. Names are written out in
 * full so that grep finds them. Signatures are those of <GL/glcorearb.h>.
 *
 * Only OpenGL 4.5 core functions belong here. Code that needs an extension checks
 * for it before calling (the pipeline statistics query only adds query targets).
 * Adding a function: one line here, nothing else.
 *
 * No include guard: the includer defines GL_FUNC, includes this file, and
 * undefines GL_FUNC again. */
#ifndef GL_FUNC
#error "define GL_FUNC(ret, name, params) before including renderers/gl/gl_funcs.h"
#endif

/* >>Context queries, errors, pixels, synchronisation of the whole pipeline */
GL_FUNC(GLenum, GetError, (void))
GL_FUNC(const GLubyte *, GetString, (GLenum name))
GL_FUNC(const GLubyte *, GetStringi, (GLenum name, GLuint index))
GL_FUNC(void, GetIntegerv, (GLenum pname, GLint *data))
GL_FUNC(void, GetInteger64v, (GLenum pname, GLint64 *data))
GL_FUNC(void, GetFloatv, (GLenum pname, GLfloat *data))
GL_FUNC(GLboolean, IsEnabled, (GLenum cap))
GL_FUNC(void, PixelStorei, (GLenum pname, GLint param))
GL_FUNC(void, ReadPixels, (GLint x, GLint y, GLsizei width, GLsizei height, GLenum format, GLenum type, void *pixels))
GL_FUNC(void, Finish, (void))
GL_FUNC(void, Flush, (void))

/* >>Fixed-function state */
GL_FUNC(void, Enable, (GLenum cap))
GL_FUNC(void, Disable, (GLenum cap))
GL_FUNC(void, Viewport, (GLint x, GLint y, GLsizei width, GLsizei height))
GL_FUNC(void, Scissor, (GLint x, GLint y, GLsizei width, GLsizei height))
GL_FUNC(void, ClearColor, (GLfloat red, GLfloat green, GLfloat blue, GLfloat alpha))
GL_FUNC(void, ClearDepth, (GLdouble depth))
GL_FUNC(void, ClearStencil, (GLint s))
GL_FUNC(void, Clear, (GLbitfield mask))
GL_FUNC(void, ColorMask, (GLboolean red, GLboolean green, GLboolean blue, GLboolean alpha))
GL_FUNC(void, DepthFunc, (GLenum func))
GL_FUNC(void, DepthMask, (GLboolean flag))
GL_FUNC(void, StencilFunc, (GLenum func, GLint ref, GLuint mask))
GL_FUNC(void, StencilFuncSeparate, (GLenum face, GLenum func, GLint ref, GLuint mask))
GL_FUNC(void, StencilOp, (GLenum fail, GLenum zfail, GLenum zpass))
GL_FUNC(void, StencilOpSeparate, (GLenum face, GLenum sfail, GLenum dpfail, GLenum dppass))
GL_FUNC(void, StencilMask, (GLuint mask))
GL_FUNC(void, StencilMaskSeparate, (GLenum face, GLuint mask))
GL_FUNC(void, BlendFunc, (GLenum sfactor, GLenum dfactor))
GL_FUNC(void, BlendFuncSeparate, (GLenum sfactorRGB, GLenum dfactorRGB, GLenum sfactorAlpha, GLenum dfactorAlpha))
GL_FUNC(void, BlendEquation, (GLenum mode))
GL_FUNC(void, BlendEquationSeparate, (GLenum modeRGB, GLenum modeAlpha))
GL_FUNC(void, CullFace, (GLenum mode))
GL_FUNC(void, FrontFace, (GLenum mode))
GL_FUNC(void, PolygonOffset, (GLfloat factor, GLfloat units))
GL_FUNC(void, PolygonMode, (GLenum face, GLenum mode))

/* >>Buffers and vertex arrays */
GL_FUNC(void, GenBuffers, (GLsizei n, GLuint *buffers))
GL_FUNC(void, DeleteBuffers, (GLsizei n, const GLuint *buffers))
GL_FUNC(void, BindBuffer, (GLenum target, GLuint buffer))
GL_FUNC(void, BufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage))
GL_FUNC(void, BufferSubData, (GLenum target, GLintptr offset, GLsizeiptr size, const void *data))
GL_FUNC(void, BufferStorage, (GLenum target, GLsizeiptr size, const void *data, GLbitfield flags))
GL_FUNC(void *, MapBufferRange, (GLenum target, GLintptr offset, GLsizeiptr length, GLbitfield access))
GL_FUNC(GLboolean, UnmapBuffer, (GLenum target))
GL_FUNC(void, FlushMappedBufferRange, (GLenum target, GLintptr offset, GLsizeiptr length))
GL_FUNC(void, BindBufferBase, (GLenum target, GLuint index, GLuint buffer))
GL_FUNC(void, BindBufferRange, (GLenum target, GLuint index, GLuint buffer, GLintptr offset, GLsizeiptr size))
GL_FUNC(void, GenVertexArrays, (GLsizei n, GLuint *arrays))
GL_FUNC(void, DeleteVertexArrays, (GLsizei n, const GLuint *arrays))
GL_FUNC(void, BindVertexArray, (GLuint array))
GL_FUNC(void, EnableVertexAttribArray, (GLuint index))
GL_FUNC(void, DisableVertexAttribArray, (GLuint index))
GL_FUNC(void, VertexAttribPointer, (GLuint index, GLint size, GLenum type, GLboolean normalized, GLsizei stride, const void *pointer))
GL_FUNC(void, VertexAttribIPointer, (GLuint index, GLint size, GLenum type, GLsizei stride, const void *pointer))
GL_FUNC(void, VertexAttribDivisor, (GLuint index, GLuint divisor))

/* >>Shaders, programs, uniforms and uniform blocks, compute */
GL_FUNC(GLuint, CreateShader, (GLenum type))
GL_FUNC(void, DeleteShader, (GLuint shader))
GL_FUNC(void, ShaderSource, (GLuint shader, GLsizei count, const GLchar *const*string, const GLint *length))
GL_FUNC(void, CompileShader, (GLuint shader))
GL_FUNC(void, GetShaderiv, (GLuint shader, GLenum pname, GLint *params))
GL_FUNC(void, GetShaderInfoLog, (GLuint shader, GLsizei bufSize, GLsizei *length, GLchar *infoLog))
GL_FUNC(GLuint, CreateProgram, (void))
GL_FUNC(void, DeleteProgram, (GLuint program))
GL_FUNC(void, AttachShader, (GLuint program, GLuint shader))
GL_FUNC(void, DetachShader, (GLuint program, GLuint shader))
GL_FUNC(void, LinkProgram, (GLuint program))
GL_FUNC(void, ValidateProgram, (GLuint program))
GL_FUNC(void, GetProgramiv, (GLuint program, GLenum pname, GLint *params))
GL_FUNC(void, GetProgramInfoLog, (GLuint program, GLsizei bufSize, GLsizei *length, GLchar *infoLog))
GL_FUNC(void, UseProgram, (GLuint program))
GL_FUNC(void, BindAttribLocation, (GLuint program, GLuint index, const GLchar *name))
GL_FUNC(void, BindFragDataLocation, (GLuint program, GLuint color, const GLchar *name))
GL_FUNC(GLint, GetAttribLocation, (GLuint program, const GLchar *name))
GL_FUNC(GLint, GetUniformLocation, (GLuint program, const GLchar *name))
GL_FUNC(void, Uniform1i, (GLint location, GLint v0))
GL_FUNC(void, Uniform1iv, (GLint location, GLsizei count, const GLint *value))
GL_FUNC(void, Uniform1f, (GLint location, GLfloat v0))
GL_FUNC(void, Uniform1fv, (GLint location, GLsizei count, const GLfloat *value))
GL_FUNC(void, Uniform2f, (GLint location, GLfloat v0, GLfloat v1))
GL_FUNC(void, Uniform2fv, (GLint location, GLsizei count, const GLfloat *value))
GL_FUNC(void, Uniform3f, (GLint location, GLfloat v0, GLfloat v1, GLfloat v2))
GL_FUNC(void, Uniform3fv, (GLint location, GLsizei count, const GLfloat *value))
GL_FUNC(void, Uniform4f, (GLint location, GLfloat v0, GLfloat v1, GLfloat v2, GLfloat v3))
GL_FUNC(void, Uniform4fv, (GLint location, GLsizei count, const GLfloat *value))
GL_FUNC(void, UniformMatrix3fv, (GLint location, GLsizei count, GLboolean transpose, const GLfloat *value))
GL_FUNC(void, UniformMatrix4fv, (GLint location, GLsizei count, GLboolean transpose, const GLfloat *value))
GL_FUNC(GLuint, GetUniformBlockIndex, (GLuint program, const GLchar *uniformBlockName))
GL_FUNC(void, GetActiveUniformBlockiv, (GLuint program, GLuint uniformBlockIndex, GLenum pname, GLint *params))
GL_FUNC(void, UniformBlockBinding, (GLuint program, GLuint uniformBlockIndex, GLuint uniformBlockBinding))
GL_FUNC(void, DispatchCompute, (GLuint num_groups_x, GLuint num_groups_y, GLuint num_groups_z))
GL_FUNC(void, MemoryBarrier, (GLbitfield barriers))
GL_FUNC(void, BindImageTexture, (GLuint unit, GLuint texture, GLint level, GLboolean layered, GLint layer, GLenum access, GLenum format))

/* >>Textures */
GL_FUNC(void, GenTextures, (GLsizei n, GLuint *textures))
GL_FUNC(void, DeleteTextures, (GLsizei n, const GLuint *textures))
GL_FUNC(void, BindTexture, (GLenum target, GLuint texture))
GL_FUNC(void, ActiveTexture, (GLenum texture))
GL_FUNC(void, TexImage2D, (GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height, GLint border, GLenum format, GLenum type, const void *pixels))
GL_FUNC(void, TexImage3D, (GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height, GLsizei depth, GLint border, GLenum format, GLenum type, const void *pixels))
GL_FUNC(void, TexSubImage2D, (GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width, GLsizei height, GLenum format, GLenum type, const void *pixels))
GL_FUNC(void, TexStorage2D, (GLenum target, GLsizei levels, GLenum internalformat, GLsizei width, GLsizei height))
GL_FUNC(void, TexStorage3D, (GLenum target, GLsizei levels, GLenum internalformat, GLsizei width, GLsizei height, GLsizei depth))
GL_FUNC(void, TexParameteri, (GLenum target, GLenum pname, GLint param))
GL_FUNC(void, TexParameterf, (GLenum target, GLenum pname, GLfloat param))
GL_FUNC(void, TexParameterfv, (GLenum target, GLenum pname, const GLfloat *params))
GL_FUNC(void, GenerateMipmap, (GLenum target))
GL_FUNC(void, GetTexImage, (GLenum target, GLint level, GLenum format, GLenum type, void *pixels))

/* >>Framebuffers and renderbuffers */
GL_FUNC(void, GenFramebuffers, (GLsizei n, GLuint *framebuffers))
GL_FUNC(void, DeleteFramebuffers, (GLsizei n, const GLuint *framebuffers))
GL_FUNC(void, BindFramebuffer, (GLenum target, GLuint framebuffer))
GL_FUNC(void, FramebufferTexture, (GLenum target, GLenum attachment, GLuint texture, GLint level))
GL_FUNC(void, FramebufferTexture2D, (GLenum target, GLenum attachment, GLenum textarget, GLuint texture, GLint level))
GL_FUNC(void, FramebufferTextureLayer, (GLenum target, GLenum attachment, GLuint texture, GLint level, GLint layer))
GL_FUNC(void, FramebufferRenderbuffer, (GLenum target, GLenum attachment, GLenum renderbuffertarget, GLuint renderbuffer))
GL_FUNC(GLenum, CheckFramebufferStatus, (GLenum target))
GL_FUNC(void, GenRenderbuffers, (GLsizei n, GLuint *renderbuffers))
GL_FUNC(void, DeleteRenderbuffers, (GLsizei n, const GLuint *renderbuffers))
GL_FUNC(void, BindRenderbuffer, (GLenum target, GLuint renderbuffer))
GL_FUNC(void, RenderbufferStorage, (GLenum target, GLenum internalformat, GLsizei width, GLsizei height))
GL_FUNC(void, RenderbufferStorageMultisample, (GLenum target, GLsizei samples, GLenum internalformat, GLsizei width, GLsizei height))
GL_FUNC(void, DrawBuffer, (GLenum buf))
GL_FUNC(void, DrawBuffers, (GLsizei n, const GLenum *bufs))
GL_FUNC(void, ReadBuffer, (GLenum src))
GL_FUNC(void, BlitFramebuffer, (GLint srcX0, GLint srcY0, GLint srcX1, GLint srcY1, GLint dstX0, GLint dstY0, GLint dstX1, GLint dstY1, GLbitfield mask, GLenum filter))
GL_FUNC(void, ClearBufferfv, (GLenum buffer, GLint drawbuffer, const GLfloat *value))
GL_FUNC(void, ClearBufferiv, (GLenum buffer, GLint drawbuffer, const GLint *value))
GL_FUNC(void, ClearBufferuiv, (GLenum buffer, GLint drawbuffer, const GLuint *value))
GL_FUNC(void, ClearBufferfi, (GLenum buffer, GLint drawbuffer, GLfloat depth, GLint stencil))
GL_FUNC(void, InvalidateFramebuffer, (GLenum target, GLsizei numAttachments, const GLenum *attachments))

/* >>Direct state access (core since 4.5): textures, framebuffers and vertex arrays
 * created and set up without binding them, so that creation never disturbs the
 * bindings the state cache (state.h) keeps */
GL_FUNC(void, CreateTextures, (GLenum target, GLsizei n, GLuint *textures))
GL_FUNC(void, TextureStorage2D, (GLuint texture, GLsizei levels, GLenum internalformat, GLsizei width, GLsizei height))
GL_FUNC(void, TextureParameteri, (GLuint texture, GLenum pname, GLint param))
GL_FUNC(void, GetTextureLevelParameteriv, (GLuint texture, GLint level, GLenum pname, GLint *params))
GL_FUNC(void, GetTextureImage, (GLuint texture, GLint level, GLenum format, GLenum type, GLsizei bufSize, void *pixels))
GL_FUNC(void, BindTextureUnit, (GLuint unit, GLuint texture))
GL_FUNC(void, CreateFramebuffers, (GLsizei n, GLuint *framebuffers))
GL_FUNC(void, NamedFramebufferTexture, (GLuint framebuffer, GLenum attachment, GLuint texture, GLint level))
GL_FUNC(void, NamedFramebufferDrawBuffers, (GLuint framebuffer, GLsizei n, const GLenum *bufs))
GL_FUNC(void, NamedFramebufferReadBuffer, (GLuint framebuffer, GLenum src))
GL_FUNC(GLenum, CheckNamedFramebufferStatus, (GLuint framebuffer, GLenum target))
GL_FUNC(void, CreateVertexArrays, (GLsizei n, GLuint *arrays))

/* >>Draws */
GL_FUNC(void, DrawArrays, (GLenum mode, GLint first, GLsizei count))
GL_FUNC(void, DrawElements, (GLenum mode, GLsizei count, GLenum type, const void *indices))
GL_FUNC(void, DrawArraysInstanced, (GLenum mode, GLint first, GLsizei count, GLsizei instancecount))
GL_FUNC(void, DrawElementsInstanced, (GLenum mode, GLsizei count, GLenum type, const void *indices, GLsizei instancecount))
GL_FUNC(void, DrawElementsBaseVertex, (GLenum mode, GLsizei count, GLenum type, const void *indices, GLint basevertex))

/* >>Queries (timer: core since 3.3; pipeline statistics: GL_ARB_pipeline_statistics_query targets) */
GL_FUNC(void, GenQueries, (GLsizei n, GLuint *ids))
GL_FUNC(void, DeleteQueries, (GLsizei n, const GLuint *ids))
GL_FUNC(void, BeginQuery, (GLenum target, GLuint id))
GL_FUNC(void, EndQuery, (GLenum target))
GL_FUNC(void, QueryCounter, (GLuint id, GLenum target))
GL_FUNC(void, GetQueryObjectiv, (GLuint id, GLenum pname, GLint *params))
GL_FUNC(void, GetQueryObjectuiv, (GLuint id, GLenum pname, GLuint *params))
GL_FUNC(void, GetQueryObjecti64v, (GLuint id, GLenum pname, GLint64 *params))
GL_FUNC(void, GetQueryObjectui64v, (GLuint id, GLenum pname, GLuint64 *params))

/* >>Sync objects */
GL_FUNC(GLsync, FenceSync, (GLenum condition, GLbitfield flags))
GL_FUNC(GLenum, ClientWaitSync, (GLsync sync, GLbitfield flags, GLuint64 timeout))
GL_FUNC(void, WaitSync, (GLsync sync, GLbitfield flags, GLuint64 timeout))
GL_FUNC(void, DeleteSync, (GLsync sync))

/* >>Debug output (core since 4.3, GL_KHR_debug) */
GL_FUNC(void, DebugMessageCallback, (GLDEBUGPROC callback, const void *userParam))
GL_FUNC(void, DebugMessageControl, (GLenum source, GLenum type, GLenum severity, GLsizei count, const GLuint *ids, GLboolean enabled))
GL_FUNC(void, DebugMessageInsert, (GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length, const GLchar *buf))
GL_FUNC(void, ObjectLabel, (GLenum identifier, GLuint name, GLsizei length, const GLchar *label))
GL_FUNC(void, PushDebugGroup, (GLenum source, GLuint id, GLsizei length, const GLchar *message))
GL_FUNC(void, PopDebugGroup, (void))
